#include "rownav/io/layout_reader.hpp"

#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "rownav/sim/plant_geometry.hpp"

namespace rownav::io {
namespace {

using nlohmann::json;

struct RawRow {
  std::vector<Eigen::Vector2d> points;  // lon/lat [deg] or x/y [m]
  std::string block;
  std::string label;  // CSV row label
  std::string where;  // position for messages
};

struct RawPlant {
  Eigen::Vector2d point;
  sim::PlantKind kind;
  std::string row_label;  // CSV: the row it belongs to; GeoJSON: empty (nearest row)
  std::string where;
};

struct RawLayout {
  std::vector<RawRow> rows;
  std::vector<RawPlant> plants;
  bool geographic = true;
};

bool plant_kind(const std::string& name, sim::PlantKind& out) {
  return core::enum_from_name(name, out) && out != sim::PlantKind::weed;
}

std::string file_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "", "cannot open file");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

int nearest_row(const sim::RowLayout& layout, const Eigen::Vector2d& p) {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < layout.rows.size(); ++i) {
    const sim::PolylinePath path(layout.rows[i].polyline);
    const double d = (path.point(path.project(p)) - p).norm();
    if (d < best_d) best_d = d, best = static_cast<int>(i);
  }
  return best;
}

/// Keeps the rows of the requested blocks; every requested block must have rows.
void keep_blocks(RawLayout& raw, const LayoutReadOptions& opt, const std::string& name) {
  for (const auto& b : opt.blocks)
    if (std::none_of(raw.rows.begin(), raw.rows.end(), [&](auto& r) { return r.block == b; }))
      throw InputError(name, "", "block '" + b + "' has no rows");
  std::erase_if(raw.rows, [&](const RawRow& r) {
    return !opt.blocks.empty() &&
           std::find(opt.blocks.begin(), opt.blocks.end(), r.block) == opt.blocks.end();
  });
}

/// Filters by block, converts to the local frame, numbers blocks and attaches plants to rows.
sim::RowLayout finish(RawLayout raw, const std::filesystem::path& file,
                      const LayoutReadOptions& opt) {
  const std::string name = file.string();
  keep_blocks(raw, opt, name);
  if (raw.rows.empty()) throw InputError(name, "", "no rows");
  std::optional<GeographicLib::LocalCartesian> enu;
  if (raw.geographic) {
    const Eigen::Vector2d first = raw.rows.front().points.front();
    const bool set = !std::isnan(opt.origin_lat_deg) && !std::isnan(opt.origin_lon_deg);
    enu.emplace(set ? opt.origin_lat_deg : first.y(), set ? opt.origin_lon_deg : first.x(), 0.0);
  }
  const auto local = [&](const Eigen::Vector2d& p) -> Eigen::Vector2d {
    if (!enu) return p;
    double x = 0.0, y = 0.0, z = 0.0;
    enu->Forward(p.y(), p.x(), 0.0, x, y, z);
    return {x, y};
  };
  sim::RowLayout out;
  out.source = name;
  std::map<std::string, int> block_ids;
  std::map<std::string, int> row_ids;
  for (const auto& r : raw.rows) {
    const auto [it, added] = block_ids.try_emplace(r.block, static_cast<int>(block_ids.size()));
    sim::RowLayout::LayoutRow row;
    row.block = it->second;
    for (const auto& p : r.points) row.polyline.push_back(local(p));
    if (sim::Row{0, 0, row.polyline}.length() <= 0.0)
      throw InputError(name, r.where, "row has zero length");
    if (!r.label.empty()) row_ids[r.label] = static_cast<int>(out.rows.size());
    out.rows.push_back(std::move(row));
  }
  for (const auto& p : raw.plants) {
    sim::Plant plant;
    plant.position = local(p.point);
    plant.kind = p.kind;
    if (p.row_label.empty()) {
      plant.row = nearest_row(out, plant.position);
    } else {
      const auto it = row_ids.find(p.row_label);
      if (it == row_ids.end()) continue;  // its row was filtered out
      plant.row = it->second;
    }
    out.plants.push_back(plant);
  }
  return out;
}

Eigen::Vector2d position(const json& c, const std::string& file, const std::string& where) {
  if (!c.is_array() || c.size() < 2 || !c[0].is_number() || !c[1].is_number())
    throw InputError(file, where, "coordinate is not [lon, lat]");
  const Eigen::Vector2d p(c[0].get<double>(), c[1].get<double>());
  if (std::abs(p.x()) > 180.0 || std::abs(p.y()) > 90.0)
    throw InputError(file, where, "coordinate out of the WGS84 lon/lat range");
  return p;
}

void add_line(RawLayout& raw, const json& coords, const std::string& block, const std::string& file,
              const std::string& where) {
  if (!coords.is_array() || coords.size() < 2)
    throw InputError(file, where, "LineString needs at least 2 positions");
  RawRow row{{}, block, "", where};
  for (const auto& c : coords) row.points.push_back(position(c, file, where));
  raw.rows.push_back(std::move(row));
}

std::string string_property(const json& props, const char* key) {
  if (!props.is_object() || !props.contains(key) || props[key].is_null()) return "";
  return props[key].is_string() ? props[key].get<std::string>() : props[key].dump();
}

void read_feature(RawLayout& raw, const json& f, const std::string& file,
                  const std::string& where) {
  if (!f.is_object()) throw InputError(file, where, "feature is not an object");
  const json& props = f.contains("properties") ? f["properties"] : json();
  if (!f.contains("geometry") || f["geometry"].is_null()) return;
  const json& g = f["geometry"];
  if (!g.is_object() || !g.contains("type") || !g["type"].is_string() || !g.contains("coordinates"))
    throw InputError(file, where, "geometry needs a type and coordinates");
  const std::string type = g["type"].get<std::string>();
  const std::string role = string_property(props, "type");
  const std::string block = string_property(props, "block");
  if (type == "LineString" && (role.empty() || role == "row")) {
    add_line(raw, g["coordinates"], block, file, where);
  } else if (type == "MultiLineString" && (role.empty() || role == "row")) {
    if (!g["coordinates"].is_array())
      throw InputError(file, where, "MultiLineString needs an array");
    for (const auto& part : g["coordinates"]) add_line(raw, part, block, file, where);
  } else if (type == "Point") {
    sim::PlantKind kind;
    if (plant_kind(string_property(props, "kind"), kind))
      raw.plants.push_back({position(g["coordinates"], file, where), kind, "", where});
  }
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) {
    const auto a = cell.find_first_not_of(" \t\r");
    const auto b = cell.find_last_not_of(" \t\r");
    out.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
  }
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

double csv_number(const std::string& cell, const std::string& column, const std::string& file,
                  const std::string& where) {
  try {
    std::size_t used = 0;
    const double v = std::stod(cell, &used);
    if (used == cell.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  throw InputError(file, where, column + ": '" + cell + "' is not a number");
}

/// Column indices of a CSV header.
struct CsvColumns {
  int row = -1, x = -1, y = -1, kind = -1, block = -1;
  bool geographic = false;
  std::size_t count = 0;
};

CsvColumns csv_columns(const std::vector<std::string>& header, const std::string& file,
                       const std::string& where) {
  CsvColumns c;
  c.count = header.size();
  int lon = -1, lat = -1;
  for (std::size_t i = 0; i < header.size(); ++i) {
    const auto& h = header[i];
    const int idx = static_cast<int>(i);
    if (h == "row")
      c.row = idx;
    else if (h == "x")
      c.x = idx;
    else if (h == "y")
      c.y = idx;
    else if (h == "lon")
      lon = idx;
    else if (h == "lat")
      lat = idx;
    else if (h == "kind")
      c.kind = idx;
    else if (h == "block")
      c.block = idx;
    else
      throw InputError(file, where, "unknown column '" + h + "'");
  }
  if (lon >= 0 && lat >= 0 && c.x < 0 && c.y < 0) c.geographic = true, c.x = lon, c.y = lat;
  if (c.row < 0 || c.x < 0 || c.y < 0)
    throw InputError(file, where, "header needs the columns row and either x,y or lon,lat");
  return c;
}

/// Adds one CSV data line to the raw layout.
void csv_line(RawLayout& raw, const CsvColumns& c, const std::vector<std::string>& cells,
              const std::string& file, const std::string& where) {
  if (cells.size() != c.count)
    throw InputError(
        file, where,
        "expected " + std::to_string(c.count) + " fields, got " + std::to_string(cells.size()));
  const auto at = [&](int i) { return cells[static_cast<std::size_t>(i)]; };
  const Eigen::Vector2d p(csv_number(at(c.x), c.geographic ? "lon" : "x", file, where),
                          csv_number(at(c.y), c.geographic ? "lat" : "y", file, where));
  if (c.geographic && (std::abs(p.x()) > 180.0 || std::abs(p.y()) > 90.0))
    throw InputError(file, where, "coordinate out of the WGS84 lon/lat range");
  const std::string label = at(c.row), block = c.block >= 0 ? at(c.block) : "";
  if (label.empty()) throw InputError(file, where, "row: empty");
  const std::string kind = c.kind >= 0 ? at(c.kind) : "row";
  sim::PlantKind pk;
  if (kind == "row") {
    auto it =
        std::find_if(raw.rows.begin(), raw.rows.end(), [&](auto& r) { return r.label == label; });
    if (it == raw.rows.end()) it = raw.rows.insert(raw.rows.end(), RawRow{{}, block, label, where});
    if (it->block != block) throw InputError(file, where, "row '" + label + "' changes block");
    it->points.push_back(p);
  } else if (plant_kind(kind, pk)) {
    raw.plants.push_back({p, pk, label, where});
  } else {
    throw InputError(
        file, where,
        "kind: unknown '" + kind + "' (expected row, vine, tree, crop, post or end_post)");
  }
}

}  // namespace

sim::RowLayout read_geojson_layout(const std::filesystem::path& file,
                                   const LayoutReadOptions& options) {
  const std::string name = file.string();
  json doc;
  try {
    doc = json::parse(file_text(file));
  } catch (const json::parse_error& e) {
    throw InputError(name, "byte " + std::to_string(e.byte), "invalid JSON");
  }
  if (!doc.is_object() || doc.value("type", "") != "FeatureCollection" ||
      !doc.contains("features") || !doc["features"].is_array())
    throw InputError(name, "", "not a GeoJSON FeatureCollection");
  RawLayout raw;
  for (std::size_t i = 0; i < doc["features"].size(); ++i)
    read_feature(raw, doc["features"][i], name, "feature " + std::to_string(i));
  return finish(std::move(raw), file, options);
}

sim::RowLayout read_csv_layout(const std::filesystem::path& file,
                               const LayoutReadOptions& options) {
  const std::string name = file.string();
  std::istringstream in(file_text(file));
  RawLayout raw;
  std::optional<CsvColumns> columns;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::string where = "line " + std::to_string(n);
    if (!columns) {
      columns = csv_columns(split_csv(line), name, where);
      raw.geographic = columns->geographic;
      continue;
    }
    csv_line(raw, *columns, split_csv(line), name, where);
  }
  if (!columns) throw InputError(name, "", "no header line");
  for (const auto& r : raw.rows)
    if (r.points.size() < 2)
      throw InputError(name, r.where, "row '" + r.label + "' has fewer than 2 points");
  for (const auto& p : raw.plants)
    if (std::none_of(raw.rows.begin(), raw.rows.end(),
                     [&](auto& r) { return r.label == p.row_label; }))
      throw InputError(name, p.where, "row '" + p.row_label + "' has no row points");
  return finish(std::move(raw), file, options);
}

sim::RowLayout read_layout(const std::filesystem::path& file, const LayoutReadOptions& options) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".geojson" || ext == ".json") return read_geojson_layout(file, options);
  if (ext == ".csv") return read_csv_layout(file, options);
  throw InputError(file.string(), "",
                   "unknown layout format '" + ext + "' (expected .geojson, .json or .csv)");
}

}  // namespace rownav::io
