#include "rownav/sim/field_config.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>

#include "rownav/sim/layout_plants.hpp"
#include "rownav/sim/plant_geometry.hpp"
#include "rownav/sim/row_dressing.hpp"

namespace rownav::sim {
namespace {

Eigen::Vector2d centroid(const std::vector<Eigen::Vector2d>& pts) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const auto& p : pts) c += p;
  return c / static_cast<double>(pts.size());
}

/// Row indices grouped by block, blocks in order of first appearance.
std::vector<std::vector<std::size_t>> rows_by_block(const RowLayout& layout) {
  std::vector<int> order;
  std::map<int, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < layout.rows.size(); ++i) {
    const int b = layout.rows[i].block;
    if (!groups.contains(b)) order.push_back(b);
    groups[b].push_back(i);
  }
  std::vector<std::vector<std::size_t>> out;
  for (int b : order) out.push_back(std::move(groups[b]));
  return out;
}

/// Plants, posts, wires and weeds of a layout (dressing plants).
void dress_plants(Field& f, const RowLayout& layout, const FieldConfig& config,
                  const TriangleMesh* instance, std::mt19937_64& rng) {
  const VineyardConfig& v = config.vineyard;
  if (layout.plants.empty()) place_vines(f, v, rng);
  build_vine_geometry(f, v, rng, instance == nullptr);
  build_layout_plants(f, layout.shapes, config.orchard, config.row_crop, rng);
  if (instance != nullptr) instance_along_rows(f, *instance, config.layout.instance_spacing);
  scatter_weeds(f, v.weeds, f.row_spacing - v.canopy_width, rng);
}

}  // namespace

void LayoutLimits::validate() const {
  core::check_range(max_extent, 1.0, 100000.0, "max_extent");
  core::check_range(max_total_row_length, 1.0, 1e7, "max_total_row_length");
  core::check_range(max_rows, 1, 1000000, "max_rows");
  core::check_range(max_plants, 0, 10000000, "max_plants");
  core::check_range(max_row_spacing, 0.5, 1000.0, "max_row_spacing");
  // A deep limit would let nested values overflow the stack again (the JSON library recurses).
  core::check_range(max_json_depth, 8, 1000, "max_json_depth");
}

void LayoutConfig::validate() const {
  core::check(!file.empty(), "file", "must name a CSV or GeoJSON layout");
  core::check_range(instance_spacing, 0.1, 100.0, "instance_spacing");
  core::check(std::isnan(origin_lat_deg) == std::isnan(origin_lon_deg), "origin_lat_deg",
              "origin_lat_deg and origin_lon_deg must both be set or both be NaN");
  if (!std::isnan(origin_lat_deg)) {
    core::check_range(origin_lat_deg, -90.0, 90.0, "origin_lat_deg");
    core::check_range(origin_lon_deg, -180.0, 180.0, "origin_lon_deg");
  }
  core::validate_nested(limits, "limits");
  core::validate_nested(terrain_transform, "terrain_transform");
  core::validate_nested(terrain_labels, "terrain_labels");
}

void FieldConfig::validate() const {
  core::check(!name.empty(), "name", "must not be empty");
  switch (kind) {
    case FieldKind::vineyard:
      core::validate_nested(vineyard, "vineyard");
      break;
    case FieldKind::orchard:
      core::validate_nested(orchard, "orchard");
      break;
    case FieldKind::row_crop:
      core::validate_nested(row_crop, "row_crop");
      break;
    case FieldKind::layout:
      core::validate_nested(layout, "layout");
      core::validate_nested(vineyard, "vineyard");
      core::validate_nested(orchard, "orchard");
      core::validate_nested(row_crop, "row_crop");
      break;
  }
  core::validate_nested(terrain, "terrain");
}

Field generate_field(const FieldConfig& config) {
  config.validate();
  Field f;
  switch (config.kind) {
    case FieldKind::vineyard:
      f = generate_vineyard(config.vineyard, config.terrain, config.seed);
      break;
    case FieldKind::orchard:
      f = generate_orchard(config.orchard, config.terrain, config.seed);
      break;
    case FieldKind::row_crop:
      f = generate_row_crop(config.row_crop, config.terrain, config.seed);
      break;
    case FieldKind::layout:
      throw std::invalid_argument("kind: layout needs its files; use io::build_field");
  }
  f.name = config.name;
  return f;
}

void order_layout_rows(RowLayout& layout) {
  std::vector<std::size_t> order;  // new position -> old index
  for (const auto& group : rows_by_block(layout)) {
    const auto longest = *std::max_element(group.begin(), group.end(), [&](auto a, auto b) {
      return Row{0, 0, layout.rows[a].polyline}.length() <
             Row{0, 0, layout.rows[b].polyline}.length();
    });
    const auto& ref = layout.rows[longest].polyline;
    const Eigen::Vector2d d = (ref.back() - ref.front()).normalized();
    const Eigen::Vector2d left(-d.y(), d.x());
    std::vector<std::pair<double, std::size_t>> keyed;
    for (std::size_t i : group) {
      auto& pl = layout.rows[i].polyline;
      if ((pl.back() - pl.front()).dot(d) < 0.0) std::reverse(pl.begin(), pl.end());
      keyed.emplace_back(left.dot(centroid(pl)), i);
    }
    std::sort(keyed.begin(), keyed.end());
    for (const auto& [key, i] : keyed) order.push_back(i);
  }
  std::vector<int> new_index(layout.rows.size(), -1);
  std::vector<RowLayout::LayoutRow> rows;
  for (std::size_t k = 0; k < order.size(); ++k) {
    new_index[order[k]] = static_cast<int>(k);
    rows.push_back(std::move(layout.rows[order[k]]));
  }
  layout.rows = std::move(rows);
  for (auto& p : layout.plants)
    if (p.row >= 0 && static_cast<std::size_t>(p.row) < new_index.size())
      p.row = new_index[static_cast<std::size_t>(p.row)];
}

double nominal_row_spacing(const FieldConfig& config) {
  switch (config.kind) {
    case FieldKind::vineyard:
      return config.vineyard.row_spacing;
    case FieldKind::orchard:
      return config.orchard.row_spacing;
    case FieldKind::row_crop:
      return config.row_crop.resolved().row_spacing;
    default:
      return 0.0;
  }
}

double estimate_row_spacing(const RowLayout& layout) {
  std::vector<double> d;
  for (std::size_t k = 0; k + 1 < layout.rows.size(); ++k) {
    if (layout.rows[k].block != layout.rows[k + 1].block) continue;
    const PolylinePath a(layout.rows[k].polyline), b(layout.rows[k + 1].polyline);
    const Eigen::Vector2d mid = b.point(0.5 * b.length());
    d.push_back((a.point(a.project(mid)) - mid).norm());
  }
  if (d.empty()) return 0.0;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

Field dress_layout(const RowLayout& layout, const FieldConfig& config, const TriangleMesh* instance,
                   const TriangleMesh* terrain_mesh) {
  core::validate_nested(config.vineyard, "vineyard");
  core::validate_nested(config.terrain, "terrain");
  if (layout.rows.empty()) throw std::invalid_argument("layout: no rows");
  const VineyardConfig& v = config.vineyard;
  std::mt19937_64 rng(config.seed);
  Field f;
  f.name = config.name;
  f.kind = FieldKind::layout;
  f.headland_width = v.headland_width;
  f.terrain = Terrain(config.terrain);
  if (terrain_mesh != nullptr) f.terrain.drape(*terrain_mesh);  // plants stand on the mesh
  const double spacing = estimate_row_spacing(layout);
  f.row_spacing = spacing > 0.0 ? spacing : v.row_spacing;
  for (std::size_t i = 0; i < layout.rows.size(); ++i)
    f.rows.push_back({static_cast<int>(i), layout.rows[i].block, layout.rows[i].polyline,
                      0.5 * v.canopy_width, v.canopy_top});
  if (!layout.plants.empty()) f.plants = layout.plants;
  apply_plant_shapes(f, layout.shapes);
  if (config.layout.dressing == LayoutDressing::plants) dress_plants(f, layout, config, instance, rng);
  if (terrain_mesh != nullptr)
    f.mesh.append(*terrain_mesh);
  else
    add_ground(f);
  return f;
}

}  // namespace rownav::sim
