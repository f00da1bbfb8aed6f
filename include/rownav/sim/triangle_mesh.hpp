#pragma once
/// @file triangle_mesh.hpp Indexed triangle soup with one surface class per triangle.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"

namespace rownav::sim {

/// What a surface is: lets the simulator label returns (ground truth) and set intensities.
enum class SurfaceClass : std::uint8_t {
  ground,
  trunk,
  canopy,
  post,
  wire,
  weed,
  crop,
  crown,
  obstacle,
  other
};

/// World-frame triangle mesh (float vertices, 32-bit indices), as Embree consumes it.
struct TriangleMesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<SurfaceClass> labels;  ///< one per triangle

  std::size_t triangle_count() const { return triangles.size(); }
  bool empty() const { return triangles.empty(); }

  /// Adds a vertex, returns its index.
  std::uint32_t add_vertex(const Eigen::Vector3f& v) {
    vertices.push_back(v);
    return static_cast<std::uint32_t>(vertices.size() - 1);
  }
  /// Adds a triangle (counter-clockwise seen from outside) with its class.
  void add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, SurfaceClass label) {
    triangles.push_back({a, b, c});
    labels.push_back(label);
  }
  /// Appends `other` transformed by T (default identity).
  void append(const TriangleMesh& other,
              const Eigen::Isometry3f& T = Eigen::Isometry3f::Identity()) {
    const auto base = static_cast<std::uint32_t>(vertices.size());
    vertices.reserve(vertices.size() + other.vertices.size());
    for (const auto& v : other.vertices) vertices.push_back(T * v);
    triangles.reserve(triangles.size() + other.triangles.size());
    for (const auto& t : other.triangles) triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    labels.insert(labels.end(), other.labels.begin(), other.labels.end());
  }
  /// Axis-aligned bounds of the vertices (empty box when there are none).
  Eigen::AlignedBox3f bounds() const {
    Eigen::AlignedBox3f b;
    for (const auto& v : vertices) b.extend(v);
    return b;
  }
};

}  // namespace rownav::sim

template <>
struct rownav::core::EnumNames<rownav::sim::SurfaceClass> {
  using E = rownav::sim::SurfaceClass;
  static constexpr std::array<std::pair<E, std::string_view>, 10> values{{{E::ground, "ground"},
                                                                         {E::trunk, "trunk"},
                                                                         {E::canopy, "canopy"},
                                                                         {E::post, "post"},
                                                                         {E::wire, "wire"},
                                                                         {E::weed, "weed"},
                                                                         {E::crop, "crop"},
                                                                         {E::crown, "crown"},
                                                                         {E::obstacle, "obstacle"},
                                                                         {E::other, "other"}}};
};
