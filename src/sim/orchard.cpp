#include "rownav/sim/orchard.hpp"

#include <algorithm>
#include <cmath>

#include "rownav/sim/plant_geometry.hpp"
#include "rownav/sim/row_dressing.hpp"

namespace rownav::sim {

double add_tree(TriangleMesh& mesh, const Eigen::Vector3f& b, const OrchardConfig& c,
                std::mt19937_64& rng) {
  using V3 = Eigen::Vector3f;
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::normal_distribution<float> n01(0.0f, 1.0f);
  const float scale = std::max(0.4f, 1.0f + static_cast<float>(c.size_variation) * n01(rng));
  const float trunk_h = static_cast<float>(c.trunk_height);
  const float cw = 0.5f * static_cast<float>(c.crown_diameter) * scale;
  const float ch = 0.5f * static_cast<float>(c.crown_height) * scale;
  add_cylinder(mesh, b - V3(0, 0, 0.05f), b + V3(0, 0, trunk_h + ch),
               0.5f * static_cast<float>(c.trunk_diameter), 8, SurfaceClass::trunk);
  const V3 centre = b + V3(0, 0, trunk_h + ch);
  const int clumps = 6 + static_cast<int>(u(rng) * 5.0f);
  float top = trunk_h;
  for (int i = 0; i < clumps; ++i) {
    // Clumps spread inside the crown ellipsoid, leaving irregular gaps and outline.
    const V3 off(0.55f * cw * n01(rng), 0.55f * cw * n01(rng), 0.45f * ch * n01(rng));
    const V3 r = V3(cw, cw, ch) * (0.35f + 0.25f * u(rng));
    V3 pos = centre + off.cwiseMax(-V3(cw, cw, ch)).cwiseMin(V3(cw, cw, ch));
    pos.z() = std::max(pos.z(), b.z() + trunk_h + r.z());
    add_blob(mesh, pos, r, 0.3f, rng, SurfaceClass::crown);
    top = std::max(top, pos.z() + r.z() - b.z());
  }
  return top;
}

void OrchardConfig::validate() const {
  core::check_range(rows, 1, 1000, "rows");
  core::check_range(row_length, 1.0, 2000.0, "row_length");
  core::check_range(row_spacing, 1.0, 15.0, "row_spacing");
  core::check_range(tree_spacing, 0.5, 15.0, "tree_spacing");
  core::check_range(trunk_diameter, 0.02, 1.0, "trunk_diameter");
  core::check_range(trunk_height, 0.1, 3.0, "trunk_height");
  core::check_range(crown_diameter, 0.2, 10.0, "crown_diameter");
  core::check_range(crown_height, 0.2, 10.0, "crown_height");
  core::check_range(size_variation, 0.0, 0.5, "size_variation");
  core::check_range(missing_trees_percent, 0.0, 100.0, "missing_trees_percent");
  core::check_range(curvature_amplitude, 0.0, 20.0, "curvature_amplitude");
  core::check_positive(curvature_wavelength, "curvature_wavelength");
  core::check_range(headland_width, 0.0, 100.0, "headland_width");
}

Field generate_orchard(const OrchardConfig& config, const TerrainConfig& terrain,
                       std::uint64_t seed) {
  config.validate();
  std::mt19937_64 rng(seed);
  Field field = make_empty_field("orchard", FieldKind::orchard, config.row_spacing,
                                 config.headland_width, terrain);
  field.rows = make_parallel_rows(config.rows, config.row_length, config.row_spacing,
                                  config.curvature_amplitude, config.curvature_wavelength,
                                  0.5 * config.crown_diameter,
                                  config.trunk_height + config.crown_height, rng);
  std::bernoulli_distribution drop(config.missing_trees_percent / 100.0);
  // Trees evenly spaced as close as possible to tree_spacing, the first and last at the row ends.
  const int per_row =
      std::max(2, static_cast<int>(std::lround(config.row_length / config.tree_spacing)) + 1);
  const double step = config.row_length / (per_row - 1);
  for (const auto& row : field.rows) {
    const PolylinePath path(row.polyline);
    for (int i = 0; i < per_row; ++i) {
      if (drop(rng)) continue;
      const Eigen::Vector2d p = path.point(i * step);
      const Eigen::Vector3f b(static_cast<float>(p.x()), static_cast<float>(p.y()),
                              static_cast<float>(field.terrain.height(p.x(), p.y())));
      const double top = add_tree(field.mesh, b, config, rng);
      field.plants.push_back({p, 0.5 * config.trunk_diameter, top, row.id, PlantKind::tree});
    }
  }
  scatter_weeds(field, config.weeds, config.row_spacing - config.crown_diameter, rng);
  add_ground(field);
  return field;
}

}  // namespace rownav::sim
