#include "rownav/sim/vineyard.hpp"

#include <algorithm>
#include <cmath>

#include "rownav/sim/plant_geometry.hpp"
#include "rownav/sim/row_dressing.hpp"

namespace rownav::sim {
namespace {

/// Canopy shape per growth stage (BACCHUS low / medium / high): clumps per metre of row, clump
/// size scale, fraction of the cordon -> canopy_top height reached, shoots per metre.
struct StageShape {
  double clumps_per_m;
  double size;
  double reach;
  double shoots_per_m;
};

StageShape stage_shape(GrowthStage s) {
  switch (s) {
    case GrowthStage::low:
      return {3.0, 0.55, 0.45, 2.0};
    case GrowthStage::medium:
      return {6.0, 0.8, 0.75, 4.0};
    case GrowthStage::high:
      break;
  }
  return {8.0, 1.0, 1.0, 5.0};
}

int draw_count(double mean, std::mt19937_64& rng) {
  return std::max(1, std::poisson_distribution<int>(mean)(rng));
}

using V3 = Eigen::Vector3f;
float f(double x) {
  return static_cast<float>(x);
}

/// One vine's frame and canopy envelope.
struct VineFrame {
  V3 base, along, across;  // ground point, unit row direction, unit left normal
  double bottom = 0.0, top = 0.0, half_width = 0.0;  // [m] canopy extent above the ground
};

/// Jittered ellipsoid clumps spread over the vine's canopy envelope, oriented with the row.
void add_clumps(TriangleMesh& mesh, const VineFrame& v, int count, double size, double spacing,
                std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> n01(0.0, 1.0);
  const V3 up = V3::UnitZ();
  for (int i = 0; i < count; ++i) {
    const double rv = std::min(0.5 * (v.top - v.bottom), (0.08 + 0.12 * u(rng)) * size);
    const double ra = (0.1 + 0.15 * u(rng)) * size;
    const double rc = v.half_width * (0.7 + 0.5 * u(rng));
    const double h = v.bottom + rv + u(rng) * std::max(0.0, v.top - v.bottom - 2.0 * rv);
    const V3 centre = v.base + f((u(rng) - 0.5) * spacing) * v.along +
                      f(0.15 * v.half_width * n01(rng)) * v.across + f(h) * up;
    add_blob(mesh, centre, V3(f(ra), f(rc), f(rv)), 0.3f, rng, SurfaceClass::canopy);
    // add_blob radii are in world axes; turn the 12 vertices just added into the row frame.
    for (std::size_t k = mesh.vertices.size() - 12; k < mesh.vertices.size(); ++k) {
      const V3 d = mesh.vertices[k] - centre;
      mesh.vertices[k] = centre + d.x() * v.along + d.y() * v.across + d.z() * up;
    }
  }
}

/// Thin shoots from inside the wall protruding up to shoot_protrusion into the inter-row.
void add_shoots(TriangleMesh& mesh, const VineFrame& v, int count, const VineyardConfig& c,
                std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const V3 up = V3::UnitZ();
  for (int i = 0; i < count; ++i) {
    const double side = u(rng) < 0.5 ? -1.0 : 1.0;
    const double h = v.bottom + u(rng) * (v.top - v.bottom);
    const double along_off = (u(rng) - 0.5) * c.plant_spacing;
    const V3 root =
        v.base + f(along_off) * v.along + f(side * 0.5 * v.half_width) * v.across + f(h) * up;
    const double reach = 1.2 * v.half_width + u(rng) * c.shoot_protrusion;
    const V3 tip = v.base + f(along_off + 0.2 * (u(rng) - 0.5)) * v.along +
                   f(side * reach) * v.across + f(h + 0.25 * u(rng)) * up;
    add_spike(mesh, root, tip, 0.02f, SurfaceClass::canopy);
  }
}

}  // namespace

void VineyardConfig::validate() const {
  core::check_range(rows, 1, 1000, "rows");
  core::check_range(row_length, 1.0, 2000.0, "row_length");
  core::check_range(row_spacing, 0.5, 10.0, "row_spacing");
  core::check_range(plant_spacing, 0.3, 5.0, "plant_spacing");
  core::check_range(trunk_diameter, 0.01, 0.5, "trunk_diameter");
  core::check_range(cordon_height_min, 0.05, 2.0, "cordon_height_min");
  core::check_range(cordon_height_max, cordon_height_min, 2.0, "cordon_height_max");
  core::check_range(canopy_top, cordon_height_max + 0.1, 5.0, "canopy_top");
  core::check_range(canopy_width, 0.05, 2.0, "canopy_width");
  core::check_range(shoot_protrusion, 0.0, 1.0, "shoot_protrusion");
  core::check_range(post_spacing, 1.0, 50.0, "post_spacing");
  core::check_range(post_diameter, 0.01, 0.5, "post_diameter");
  core::check_range(end_post_diameter, 0.01, 0.5, "end_post_diameter");
  core::check_range(wire_count, 0, 10, "wire_count");
  core::check_range(wire_diameter, 0.0005, 0.05, "wire_diameter");
  core::check_range(missing_plants_percent, 0.0, 100.0, "missing_plants_percent");
  core::check_range(gap_count, 0, 10000, "gap_count");
  core::check_range(gap_length_plants, 1, 1000, "gap_length_plants");
  core::check_range(curvature_amplitude, 0.0, 20.0, "curvature_amplitude");
  core::check_positive(curvature_wavelength, "curvature_wavelength");
  core::check_range(headland_width, 0.0, 100.0, "headland_width");
  core::check_range(hedge_roundness, 1.0, 50.0, "hedge_roundness");
  core::check_range(hedge_roughness, 0.0, 0.5, "hedge_roughness");
}

double add_vine(TriangleMesh& mesh, const Eigen::Vector3d& base, const Eigen::Vector2d& tangent,
                const VineyardConfig& c, std::mt19937_64& rng) {
  if (c.canopy_shape == CanopyShape::solid_hedge) return add_hedge_segment(mesh, base, tangent, c, rng);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const StageShape shape = stage_shape(c.stage);
  VineFrame v;
  v.base = base.cast<float>();
  v.along = V3(f(tangent.x()), f(tangent.y()), 0.0f);
  v.across = V3(-v.along.y(), v.along.x(), 0.0f);
  const V3 up = V3::UnitZ();
  const double cordon = c.cordon_height_min + u(rng) * (c.cordon_height_max - c.cordon_height_min);
  add_cylinder(mesh, v.base - 0.05f * up, v.base + f(cordon) * up, f(0.5 * c.trunk_diameter), 8,
               SurfaceClass::trunk);
  const V3 arm = f(0.5 * c.plant_spacing) * v.along;
  const V3 cordon_pt = v.base + f(cordon) * up;
  add_cylinder(mesh, cordon_pt - arm, cordon_pt + arm, f(0.3 * c.trunk_diameter), 4,
               SurfaceClass::trunk);
  // Vigour varies from vine to vine: the wall thickness and height are irregular along the row.
  const double vigour = 0.7 + 0.6 * u(rng);
  v.bottom = cordon + 0.05;
  v.top = v.bottom + (c.canopy_top - v.bottom) * shape.reach * std::min(1.0, 0.75 + 0.25 * vigour);
  v.half_width = 0.5 * c.canopy_width * shape.size * vigour;
  add_clumps(mesh, v, draw_count(shape.clumps_per_m * c.plant_spacing, rng), shape.size,
             c.plant_spacing, rng);
  add_shoots(mesh, v, draw_count(shape.shoots_per_m * c.plant_spacing, rng), c, rng);
  return v.top;
}

Field generate_vineyard(const VineyardConfig& config, const TerrainConfig& terrain,
                        std::uint64_t seed) {
  config.validate();
  std::mt19937_64 rng(seed);
  Field field = make_empty_field("vineyard", FieldKind::vineyard, config.row_spacing,
                                 config.headland_width, terrain);
  field.rows = make_parallel_rows(config.rows, config.row_length, config.row_spacing,
                                  config.curvature_amplitude, config.curvature_wavelength,
                                  0.5 * config.canopy_width, config.canopy_top, rng);
  place_vines(field, config, rng);
  build_vine_geometry(field, config, rng);
  scatter_weeds(field, config.weeds, config.row_spacing - config.canopy_width, rng);
  add_ground(field);
  return field;
}

}  // namespace rownav::sim
