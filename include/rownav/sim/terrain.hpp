#pragma once
/// @file terrain.hpp Ground height field: a plane with slope plus smooth seeded roughness.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/sim/triangle_mesh.hpp"

namespace rownav::sim {

/// Terrain shape. Heights are relative to z = 0 at the field origin.
struct TerrainConfig {
  double slope_x_deg = 0.0;     ///< [deg] slope along world x (positive: ground rises with x)
  double slope_y_deg = 0.0;     ///< [deg] slope along world y
  double roughness = 0.02;      ///< [m] std-dev of the smooth height noise (0 = flat)
  double roughness_wavelength = 2.0;  ///< [m] correlation length of the height noise
  double cell_size = 0.5;       ///< [m] ground mesh resolution
  std::uint64_t seed = 1;       ///< noise seed

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("slope_x_deg", s.slope_x_deg);
    v("slope_y_deg", s.slope_y_deg);
    v("roughness", s.roughness);
    v("roughness_wavelength", s.roughness_wavelength);
    v("cell_size", s.cell_size);
    v("seed", s.seed);
  }
  void validate() const;
};

class RayCaster;

/// Deterministic height field z(x, y) for a given config, optionally draped over a ground mesh
/// (an imported terrain: heights then come from ray casts straight down onto the mesh).
class Terrain {
 public:
  Terrain() = default;
  explicit Terrain(const TerrainConfig& config);

  /// Drapes the terrain over the triangles of `mesh` labelled SurfaceClass::ground (the rest is
  /// ignored, so canopy over the ground is not ridden on): height() and normal() then come from
  /// a ray cast straight down onto them; where no ground triangle lies under (x, y), from the
  /// procedural surface of the config. A mesh without ground triangles leaves it undraped.
  void drape(const TriangleMesh& mesh);
  /// True when drape() found ground triangles.
  bool draped() const { return ground_ != nullptr; }

  /// [m] ground height at world (x, y).
  double height(double x, double y) const;
  /// Unit surface normal at (x, y) (of the triangle hit when draped).
  Eigen::Vector3d normal(double x, double y) const;
  /// Triangulated ground over [min, max] at config.cell_size, labelled SurfaceClass::ground.
  TriangleMesh mesh(const Eigen::Vector2d& min, const Eigen::Vector2d& max) const;
  const TerrainConfig& config() const { return config_; }

 private:
  TerrainConfig config_;
  double gx_ = 0.0, gy_ = 0.0;  // tan(slope)
  std::vector<double> phase_;   // noise phases / directions derived from the seed
  // Draped: ground triangles (shared by copies: the field, the simulator) and the height the
  // downward rays start from, above the mesh's top.
  std::shared_ptr<const RayCaster> ground_;
  float ray_top_ = 0.0f, ray_length_ = 0.0f;
  bool cast_down(double x, double y, double& z, Eigen::Vector3d* n) const;
};

}  // namespace rownav::sim
