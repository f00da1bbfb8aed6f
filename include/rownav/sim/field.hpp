#pragma once
/// @file field.hpp A simulated field: semantic layout (rows, plants, posts) plus its geometry.
///
/// World frame: east-north-up for imported layouts, otherwise x along the rows, y across them,
/// z up. Rows are ordered by their lateral position within a block; corridor k of a block lies
/// between its rows k and k+1 (the papers' "lane"); the space beside the first and last rows is
/// an "alley" (Emmi 2021, 002_806e72d300173f73.txt sec. "field model").
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/sim/terrain.hpp"
#include "rownav/sim/triangle_mesh.hpp"

namespace rownav::sim {

/// Kind of field a generator produced.
enum class FieldKind : std::uint8_t { vineyard, orchard, row_crop, layout };

/// Kind of object on the ground; every one has a footprint used for crushed-plant counting.
enum class PlantKind : std::uint8_t { vine, tree, crop, weed, post, end_post };

/// A plant, weed or post at ground level.
struct Plant {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  ///< [m] world x, y of the stem / post
  double radius = 0.05;  ///< [m] footprint radius (a robot footprint over it crushes it)
  double height = 1.0;   ///< [m] above the ground
  int row = -1;          ///< index into Field::rows, -1 for inter-row weeds
  PlantKind kind = PlantKind::vine;
};

/// One crop row: its centre line from the first to the last plant (or end post).
struct Row {
  int id = 0;                             ///< index in Field::rows
  int block = 0;                          ///< block the row belongs to (imported layouts)
  std::vector<Eigen::Vector2d> polyline;  ///< [m] world, >= 2 points, start -> end
  double half_width = 0.3;  ///< [m] half the canopy width (solid obstacle around the line)
  double height = 1.8;      ///< [m] top of the canopy above the ground

  const Eigen::Vector2d& start() const { return polyline.front(); }
  const Eigen::Vector2d& end() const { return polyline.back(); }
  /// [m] length along the polyline.
  double length() const {
    double l = 0.0;
    for (std::size_t i = 1; i < polyline.size(); ++i) l += (polyline[i] - polyline[i - 1]).norm();
    return l;
  }
};

/// A complete simulated field.
struct Field {
  std::string name = "field";
  FieldKind kind = FieldKind::vineyard;
  std::vector<Row> rows;       ///< ordered by lateral position within each block
  std::vector<Plant> plants;   ///< vines / trees / crops, weeds, posts
  double row_spacing = 2.0;    ///< [m] nominal distance between adjacent row centre lines
  double headland_width = 6.0; ///< [m] free space beyond the row ends
  Terrain terrain;
  TriangleMesh mesh;           ///< every surface a LiDAR can hit, ground included

  /// Axis-aligned bounds of the rows' polylines (without headlands).
  Eigen::AlignedBox2d row_bounds() const {
    Eigen::AlignedBox2d b;
    for (const auto& r : rows)
      for (const auto& p : r.polyline) b.extend(p);
    return b;
  }
};

/// Per-plant sizes an imported layout may give (CSV columns / GeoJSON properties of the same
/// names); NaN: the dressing config's value (FieldConfig::orchard for trees, row_crop for crops).
struct PlantShape {
  double trunk_diameter = std::numeric_limits<double>::quiet_NaN();  ///< [m] tree trunk
  double trunk_height = std::numeric_limits<double>::quiet_NaN();    ///< [m] ground to crown
  double crown_diameter = std::numeric_limits<double>::quiet_NaN();  ///< [m] tree crown width
  double crown_height = std::numeric_limits<double>::quiet_NaN();    ///< [m] crown extent
  double height = std::numeric_limits<double>::quiet_NaN();  ///< [m] crop plant / post height
  double width = std::numeric_limits<double>::quiet_NaN();   ///< [m] crop plant / post diameter
};

/// Imported geometry: rows as polylines and optional plant / post positions, e.g. from a
/// GeoJSON or CSV layout already converted to a local metric frame.
struct RowLayout {
  struct LayoutRow {
    std::vector<Eigen::Vector2d> polyline;  ///< [m] local frame
    int block = 0;
  };
  std::vector<LayoutRow> rows;
  std::vector<Plant> plants;  ///< explicit plants / posts; empty: the builder places them
  std::vector<PlantShape> shapes;  ///< one per plant (or empty: every size from the config)
  std::string source;         ///< file it came from, for messages
};

}  // namespace rownav::sim

template <>
struct rownav::core::EnumNames<rownav::sim::FieldKind> {
  using E = rownav::sim::FieldKind;
  static constexpr std::array<std::pair<E, std::string_view>, 4> values{
      {{E::vineyard, "vineyard"}, {E::orchard, "orchard"}, {E::row_crop, "row_crop"},
       {E::layout, "layout"}}};
};

template <>
struct rownav::core::EnumNames<rownav::sim::PlantKind> {
  using E = rownav::sim::PlantKind;
  static constexpr std::array<std::pair<E, std::string_view>, 6> values{
      {{E::vine, "vine"}, {E::tree, "tree"}, {E::crop, "crop"}, {E::weed, "weed"},
       {E::post, "post"}, {E::end_post, "end_post"}}};
};
