#include "rownav/sim/layout_plants.hpp"

#include <algorithm>
#include <cmath>

namespace rownav::sim {
namespace {

double or_default(double given, double fallback) { return std::isnan(given) ? fallback : given; }

OrchardConfig tree_config(const OrchardConfig& base, const PlantShape& s) {
  OrchardConfig c = base;
  c.trunk_diameter = or_default(s.trunk_diameter, c.trunk_diameter);
  c.trunk_height = or_default(s.trunk_height, c.trunk_height);
  c.crown_diameter = or_default(s.crown_diameter, c.crown_diameter);
  c.crown_height = or_default(s.crown_height, c.crown_height);
  core::validate_nested(c, "orchard (a tree of the layout)");
  return c;
}

Eigen::Vector3f ground_at(const Field& field, const Eigen::Vector2d& p) {
  return {static_cast<float>(p.x()), static_cast<float>(p.y()),
          static_cast<float>(field.terrain.height(p.x(), p.y()))};
}

/// Rows holding trees take the mean crown half width and the highest tree top.
void fit_rows_to_trees(Field& field, const std::vector<double>& crown_half_widths) {
  std::vector<double> sum(field.rows.size(), 0.0), top(field.rows.size(), 0.0);
  std::vector<int> n(field.rows.size(), 0);
  for (std::size_t i = 0; i < field.plants.size(); ++i) {
    const Plant& p = field.plants[i];
    if (p.kind != PlantKind::tree || p.row < 0) continue;
    const auto r = static_cast<std::size_t>(p.row);
    sum[r] += crown_half_widths[i], top[r] = std::max(top[r], p.height), ++n[r];
  }
  for (std::size_t r = 0; r < field.rows.size(); ++r)
    if (n[r] > 0) field.rows[r].half_width = sum[r] / n[r], field.rows[r].height = top[r];
}

}  // namespace

void apply_plant_shapes(Field& field, const std::vector<PlantShape>& shapes) {
  for (std::size_t i = 0; i < shapes.size() && i < field.plants.size(); ++i) {
    Plant& p = field.plants[i];
    if (p.kind == PlantKind::tree || p.kind == PlantKind::vine) continue;
    p.height = or_default(shapes[i].height, p.height);
    p.radius = 0.5 * or_default(shapes[i].width, 2.0 * p.radius);
  }
}

void build_layout_plants(Field& field, const std::vector<PlantShape>& shapes,
                         const OrchardConfig& orchard, const RowCropConfig& row_crop,
                         std::mt19937_64& rng) {
  const CropPreset crop = row_crop.resolved();
  std::vector<double> crown_half(field.plants.size(), 0.0);
  for (std::size_t i = 0; i < field.plants.size(); ++i) {
    Plant& p = field.plants[i];
    const PlantShape s = i < shapes.size() ? shapes[i] : PlantShape{};
    if (p.kind == PlantKind::tree) {
      const OrchardConfig c = tree_config(orchard, s);
      p.height = add_tree(field.mesh, ground_at(field, p.position), c, rng);
      p.radius = 0.5 * c.trunk_diameter;
      crown_half[i] = 0.5 * c.crown_diameter;
    } else if (p.kind == PlantKind::crop) {
      const double h = or_default(s.height, crop.plant_height);
      const double w = or_default(s.width, crop.plant_width);
      add_crop_plant(field.mesh, ground_at(field, p.position), row_crop.crop,
                     static_cast<float>(h), static_cast<float>(w), rng);
      p.height = h;
      p.radius = 0.5 * std::min(w, crop.crush_diameter);
    }
  }
  fit_rows_to_trees(field, crown_half);
}

}  // namespace rownav::sim
