#pragma once
/// @file mesh_labels.hpp Labels the parts of an unlabelled field mesh (a photogrammetric /
/// height-map mesh: ground and canopy in one surface) by a height rule, so the robot rides the
/// ground part (Terrain::drape) and the LiDAR labels canopy returns (issue 10).
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"
#include "rownav/sim/triangle_mesh.hpp"

namespace rownav::sim {

/// How an imported terrain mesh is labelled.
enum class MeshLabelRule : std::uint8_t {
  ground,  ///< every triangle is ground (a bare terrain mesh)
  height,  ///< by height above the local ground: ground, else canopy
};

/// Height rule: the local ground is the lowest vertex within one cell around a triangle.
struct MeshLabelConfig {
  MeshLabelRule rule = MeshLabelRule::ground;  ///< ground: the behaviour before issue 10
  /// [m] grid cell of the local-ground minimum: wider than a row's canopy (a vine row ~0.5-1 m,
  /// a crown ~4 m), so every cell around a canopy triangle reaches bare ground
  double cell_size = 2.0;
  /// [m] triangles whose centroid is at most this far above the local ground are ground
  /// (grass, ruts); above: canopy
  double ground_band = 0.25;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("rule", s.rule);
    v("cell_size", s.cell_size);
    v("ground_band", s.ground_band);
  }
  void validate() const;
};

/// Relabels `mesh` by `config` (rule ground: every triangle ground). Rule height also adds,
/// under every canopy triangle, a ground copy of it at the local ground height (the lowest
/// vertex within about cell_size: on a slope this sits up to ~slope x cell_size low).
void label_mesh(TriangleMesh& mesh, const MeshLabelConfig& config);

}  // namespace rownav::sim

template <>
struct rownav::core::EnumNames<rownav::sim::MeshLabelRule> {
  using E = rownav::sim::MeshLabelRule;
  static constexpr std::array<std::pair<E, std::string_view>, 2> values{
      {{E::ground, "ground"}, {E::height, "height"}}};
};
