#include "rownav/sim/orchard.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "rownav/sim/plant_geometry.hpp"
#include "rownav/sim/row_dressing.hpp"

namespace rownav::sim {

double add_tree(TriangleMesh& mesh, const Eigen::Vector3f& b, const OrchardConfig& c,
                std::mt19937_64& rng, const Eigen::Vector2d& along, double along_radius) {
  using V3 = Eigen::Vector3f;
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::normal_distribution<float> n01(0.0f, 1.0f);
  const float scale = std::max(0.4f, 1.0f + static_cast<float>(c.size_variation) * n01(rng));
  const float trunk_h = static_cast<float>(c.trunk_height);
  const float cw = 0.5f * static_cast<float>(c.crown_diameter) * scale;
  const float ch = 0.5f * static_cast<float>(c.crown_height) * scale;
  // Semi-axis along the row (= cw for a round crown) and the world-axis extents of the crown.
  const float ra = along_radius > 0.0 ? static_cast<float>(along_radius) : cw;
  const Eigen::Vector2f a = along.cast<float>(), left(-a.y(), a.x());
  const V3 ext(std::abs(a.x()) * ra + std::abs(a.y()) * cw,
               std::abs(a.y()) * ra + std::abs(a.x()) * cw, ch);
  add_cylinder(mesh, b - V3(0, 0, 0.05f), b + V3(0, 0, trunk_h + ch),
               0.5f * static_cast<float>(c.trunk_diameter), 8, SurfaceClass::trunk);
  const V3 centre = b + V3(0, 0, trunk_h + ch);
  const int clumps = 6 + static_cast<int>(u(rng) * 5.0f);
  float top = trunk_h;
  for (int i = 0; i < clumps; ++i) {
    // Clumps spread inside the crown ellipsoid, leaving irregular gaps and outline.
    const V3 local(0.55f * ra * n01(rng), 0.55f * cw * n01(rng), 0.45f * ch * n01(rng));
    const V3 off(a.x() * local.x() + left.x() * local.y(),
                 a.y() * local.x() + left.y() * local.y(), local.z());
    const V3 r = ext * (0.35f + 0.25f * u(rng));
    V3 pos = centre + off.cwiseMax(-ext).cwiseMin(ext);
    pos.z() = std::max(pos.z(), b.z() + trunk_h + r.z());
    add_blob(mesh, pos, r, 0.3f, rng, SurfaceClass::crown);
    top = std::max(top, pos.z() + r.z() - b.z());
  }
  return top;
}

namespace {

/// Per row, the slots removed by config.gap_count runs of gap_length_trees consecutive trees.
std::vector<std::vector<bool>> gap_slots(const OrchardConfig& c, int rows, int per_row,
                                         std::mt19937_64& rng) {
  std::vector<std::vector<bool>> gaps(static_cast<std::size_t>(rows),
                                      std::vector<bool>(static_cast<std::size_t>(per_row), false));
  if (c.gap_count <= 0) return gaps;  // no draws: fields without gaps are unchanged
  const int len = std::min(c.gap_length_trees, per_row);
  std::uniform_int_distribution<int> row(0, rows - 1), start(0, per_row - len);
  for (int g = 0; g < c.gap_count; ++g) {
    auto& r = gaps[static_cast<std::size_t>(row(rng))];
    const int s = start(rng);
    std::fill(r.begin() + s, r.begin() + s + len, true);
  }
  return gaps;
}

/// Trees evenly spaced as close as possible to tree_spacing, the first and last at the row ends.
void place_row_trees(Field& field, const Row& row, const OrchardConfig& c, int per_row,
                     const std::vector<bool>& gap, std::mt19937_64& rng) {
  std::bernoulli_distribution drop(c.missing_trees_percent / 100.0);
  std::normal_distribution<double> n01(0.0, 1.0);
  const double step = c.row_length / (per_row - 1);
  const bool hedge = c.form == OrchardForm::hedgerow;
  const PolylinePath path(row.polyline);
  for (int i = 0; i < per_row; ++i) {
    if (drop(rng) || gap[static_cast<std::size_t>(i)]) continue;
    const double s = i * step;
    Eigen::Vector2d p = path.point(s);
    if (c.position_jitter > 0.0)
      p += c.position_jitter * (n01(rng) * path.tangent(s) + n01(rng) * path.left(s));
    OrchardConfig tree = c;
    if (c.trunk_variation > 0.0)
      tree.trunk_diameter = std::clamp(c.trunk_diameter * (1.0 + c.trunk_variation * n01(rng)),
                                       0.5 * c.trunk_diameter, 2.0 * c.trunk_diameter);
    const Eigen::Vector3f b(static_cast<float>(p.x()), static_cast<float>(p.y()),
                            static_cast<float>(field.terrain.height(p.x(), p.y())));
    // Round crowns keep the world axes (fields without hedgerows are unchanged).
    const double top =
        hedge ? add_tree(field.mesh, b, tree, rng, path.tangent(s), c.hedge_overlap * c.tree_spacing)
              : add_tree(field.mesh, b, tree, rng);
    field.plants.push_back({p, 0.5 * tree.trunk_diameter, top, row.id, PlantKind::tree});
  }
}

}  // namespace

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
  core::check_range(hedge_overlap, 0.5, 3.0, "hedge_overlap");
  core::check_range(trunk_variation, 0.0, 0.5, "trunk_variation");
  core::check_range(position_jitter, 0.0, 2.0, "position_jitter");
  core::check_range(gap_count, 0, 10000, "gap_count");
  core::check_range(gap_length_trees, 1, 1000, "gap_length_trees");
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
  const int per_row =
      std::max(2, static_cast<int>(std::lround(config.row_length / config.tree_spacing)) + 1);
  const auto gaps = gap_slots(config, static_cast<int>(field.rows.size()), per_row, rng);
  for (const auto& row : field.rows)
    place_row_trees(field, row, config, per_row, gaps[static_cast<std::size_t>(row.id)], rng);
  scatter_weeds(field, config.weeds, config.row_spacing - config.crown_diameter, rng);
  add_ground(field);
  return field;
}

}  // namespace rownav::sim
