#pragma once
/// @file plant_geometry.hpp Low-poly primitives the field generators build plants from, and an
/// arc-length walker over row polylines. Kept cheap for ray casting: 8-sided trunks, 20-triangle
/// jittered foliage clumps, 4-sided wires.
#include <Eigen/Core>
#include <random>
#include <vector>

#include "rownav/sim/triangle_mesh.hpp"

namespace rownav::sim {

/// Open cylinder (no caps) with `sides` faces from `a` to `b`; with `cap` a fan closes the top.
/// Also used for posts (6-8 sides) and wires (4 sides, a thin square tube).
void add_cylinder(TriangleMesh& mesh, const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                  float radius, int sides, SurfaceClass label, bool cap = false);

/// Jittered ellipsoid blob centred at `c` with semi-axes `radii`: an icosahedron (20 triangles)
/// or, when `coarse`, an octahedron (8 triangles), each vertex pushed radially by a factor in
/// [1 - jitter, 1 + jitter]. Foliage clumps, tree crowns, weed tufts, cabbage heads.
void add_blob(TriangleMesh& mesh, const Eigen::Vector3f& c, const Eigen::Vector3f& radii,
              float jitter, std::mt19937_64& rng, SurfaceClass label, bool coarse = false);

/// Three-sided pyramid from a base of radius `base_radius` around `base` to the point `tip`
/// (3 triangles): protruding shoots.
void add_spike(TriangleMesh& mesh, const Eigen::Vector3f& base, const Eigen::Vector3f& tip,
               float base_radius, SurfaceClass label);

/// Flat leaf / blade from `base` to `tip` with width `width` across `side` (2 triangles).
void add_blade(TriangleMesh& mesh, const Eigen::Vector3f& base, const Eigen::Vector3f& tip,
               const Eigen::Vector3f& side, float width, SurfaceClass label);

/// Arc-length parametrisation of a 2D polyline (>= 2 points).
class PolylinePath {
 public:
  explicit PolylinePath(std::vector<Eigen::Vector2d> points);
  /// [m] total length.
  double length() const { return cumulative_.back(); }
  /// Point at arc length s (clamped to [0, length]).
  Eigen::Vector2d point(double s) const;
  /// Unit tangent at arc length s.
  Eigen::Vector2d tangent(double s) const;
  /// Unit left normal at arc length s (tangent rotated by +90 deg).
  Eigen::Vector2d left(double s) const {
    const Eigen::Vector2d t = tangent(s);
    return {-t.y(), t.x()};
  }
  /// Arc length of the point of the polyline nearest to p.
  double project(const Eigen::Vector2d& p) const;
  const std::vector<Eigen::Vector2d>& points() const { return points_; }

 private:
  std::size_t segment(double s) const;
  std::vector<Eigen::Vector2d> points_;
  std::vector<double> cumulative_;
};

}  // namespace rownav::sim
