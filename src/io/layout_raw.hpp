#pragma once
// Private to rownav_io: a layout as read from GeoJSON or CSV, before it is checked against
// sim::LayoutLimits and converted to the local frame (layout_reader.cpp, layout_csv_reader.cpp).
#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <utility>
#include <string>
#include <vector>

#include "rownav/io/layout_reader.hpp"

namespace rownav::io::detail {

struct RawRow {
  std::vector<Eigen::Vector2d> points;  // lon/lat [deg] or x/y [m]
  std::string block;
  std::string label;                      // CSV row label
  std::string where;                      // position for messages
  std::vector<std::string> point_wheres;  // CSV: the line of each point (GeoJSON: empty)
};

struct RawPlant {
  Eigen::Vector2d point;
  sim::PlantKind kind;
  std::string row_label;  // CSV: the row it belongs to; GeoJSON: empty (nearest row)
  std::string where;
  sim::PlantShape shape = {};  // sizes given in the file (NaN: not given)
};

/// The PlantShape members by column / property name, for both readers.
inline constexpr std::array<std::pair<const char*, double sim::PlantShape::*>, 6> kShapeKeys{{
    {"trunk_diameter", &sim::PlantShape::trunk_diameter},
    {"trunk_height", &sim::PlantShape::trunk_height},
    {"crown_diameter", &sim::PlantShape::crown_diameter},
    {"crown_height", &sim::PlantShape::crown_height},
    {"height", &sim::PlantShape::height},
    {"width", &sim::PlantShape::width}}};

struct RawLayout {
  std::vector<RawRow> rows;
  std::vector<RawPlant> plants;
  bool geographic = true;
  sim::LayoutLimits limits;

  // Counted while reading: a CSV row is looked up by label, quadratic in the row count.
  void add_row(RawRow row, const std::string& file) {
    if (rows.size() >= static_cast<std::size_t>(limits.max_rows))
      throw InputError(
          file, row.where,
          "layout.limits.max_rows: more than " + std::to_string(limits.max_rows) + " rows");
    rows.push_back(std::move(row));
  }
  void add_plant(RawPlant plant, const std::string& file) {
    if (plants.size() >= static_cast<std::size_t>(limits.max_plants))
      throw InputError(
          file, plant.where,
          "layout.limits.max_plants: more than " + std::to_string(limits.max_plants) + " plants");
    plants.push_back(std::move(plant));
  }
};

/// True for a PlantKind name other than weed.
bool plant_kind(const std::string& name, sim::PlantKind& out);
/// The whole file; InputError "cannot open file".
std::string file_text(const std::filesystem::path& file);
/// Keeps the requested blocks, converts to the local frame (ENU for geographic layouts),
/// checks the extent and total row length, numbers blocks and attaches plants to rows.
sim::RowLayout finish_layout(RawLayout raw, const std::filesystem::path& file,
                             const LayoutReadOptions& opt);

}  // namespace rownav::io::detail
