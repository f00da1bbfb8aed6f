#include "rownav/io/layout_reader.hpp"

#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "layout_limits.hpp"
#include "layout_raw.hpp"
#include "rownav/sim/plant_geometry.hpp"

namespace rownav::io {
namespace detail {
namespace {

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

/// WGS84 lon/lat -> local east-north [m] (identity for metric layouts).
class ToLocal {
 public:
  ToLocal(const RawLayout& raw, const LayoutReadOptions& opt) {
    if (!raw.geographic) return;
    const Eigen::Vector2d first = raw.rows.front().points.front();
    const bool set = !std::isnan(opt.origin_lat_deg) && !std::isnan(opt.origin_lon_deg);
    enu_.emplace(set ? opt.origin_lat_deg : first.y(), set ? opt.origin_lon_deg : first.x(), 0.0);
  }
  Eigen::Vector2d operator()(const Eigen::Vector2d& p) const {
    if (!enu_) return p;
    double x = 0.0, y = 0.0, z = 0.0;
    enu_->Forward(p.y(), p.x(), 0.0, x, y, z);
    return {x, y};
  }

 private:
  std::optional<GeographicLib::LocalCartesian> enu_;
};

/// Converts and numbers the rows; `located` gets every row point, returns the total length.
double add_rows(const RawLayout& raw, const ToLocal& local, const std::string& name,
                sim::RowLayout& out, std::map<std::string, int>& row_ids,
                std::vector<LocatedPoint>& located) {
  std::map<std::string, int> block_ids;
  double total_length = 0.0;
  for (const auto& r : raw.rows) {
    const auto [it, added] = block_ids.try_emplace(r.block, static_cast<int>(block_ids.size()));
    sim::RowLayout::LayoutRow row;
    row.block = it->second;
    for (std::size_t k = 0; k < r.points.size(); ++k) {
      row.polyline.push_back(local(r.points[k]));
      located.push_back(
          {row.polyline.back(), r.point_wheres.empty() ? &r.where : &r.point_wheres[k]});
    }
    const double length = sim::Row{0, 0, row.polyline}.length();
    if (length <= 0.0) throw InputError(name, r.where, "row has zero length");
    total_length += length;
    if (!r.label.empty()) row_ids[r.label] = static_cast<int>(out.rows.size());
    out.rows.push_back(std::move(row));
  }
  return total_length;
}

/// Plants of kept rows (CSV: by label; GeoJSON: all), converted; `located` gets each point.
std::vector<std::pair<const RawPlant*, sim::Plant>> kept_plants(
    const RawLayout& raw, const ToLocal& local, const std::map<std::string, int>& row_ids,
    std::vector<LocatedPoint>& located) {
  std::vector<std::pair<const RawPlant*, sim::Plant>> out;
  for (const auto& p : raw.plants) {
    sim::Plant plant;
    plant.position = local(p.point);
    plant.kind = p.kind;
    if (!p.row_label.empty()) {
      const auto it = row_ids.find(p.row_label);
      if (it == row_ids.end()) continue;  // its row was filtered out
      plant.row = it->second;
    }
    out.emplace_back(&p, plant);
    located.push_back({out.back().second.position, &p.where});
  }
  return out;
}

}  // namespace

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

sim::RowLayout finish_layout(RawLayout raw, const std::filesystem::path& file,
                             const LayoutReadOptions& opt) {
  const std::string name = file.string();
  keep_blocks(raw, opt, name);
  if (raw.rows.empty()) throw InputError(name, "", "no rows");
  const ToLocal local(raw, opt);
  sim::RowLayout out;
  out.source = name;
  std::map<std::string, int> row_ids;
  std::vector<LocatedPoint> located;
  const double total_length = add_rows(raw, local, name, out, row_ids, located);
  auto plants = kept_plants(raw, local, row_ids, located);
  // The extent first: one far-off point is the usual cause of both, and this error names it.
  check_layout_extent(located, opt.limits, name);
  if (total_length > opt.limits.max_total_row_length)
    throw InputError(name, "",
                     "layout.limits.max_total_row_length: the rows add up to " +
                         core::detail::show(total_length) + " m, more than " +
                         core::detail::show(opt.limits.max_total_row_length) + " m");
  for (auto& [raw_plant, plant] : plants) {
    if (raw_plant->row_label.empty()) plant.row = nearest_row(out, plant.position);
    out.plants.push_back(plant);
    out.shapes.push_back(raw_plant->shape);
  }
  return out;
}

}  // namespace detail

namespace {

using detail::RawLayout;
using detail::RawPlant;
using detail::RawRow;
using nlohmann::json;

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
  RawRow row{{}, block, "", where, {}};
  for (const auto& c : coords) row.points.push_back(position(c, file, where));
  raw.add_row(std::move(row), file);
}

/// A name-like property: a string as it is, a number or boolean as JSON text, "" when absent.
/// An array or object is refused rather than dumped: the message would carry all of it.
std::string string_property(const json& props, const char* key, const std::string& file,
                            const std::string& where) {
  if (!props.is_object() || !props.contains(key) || props[key].is_null()) return "";
  const json& v = props[key];
  if (v.is_structured())
    throw InputError(file, where,
                     std::string("properties.") + key + ": expected a string or a number");
  return v.is_string() ? v.get<std::string>() : v.dump();
}

/// The sizes among a Point's properties (detail::kShapeKeys): positive finite numbers [m].
sim::PlantShape plant_shape(const json& props, const std::string& file, const std::string& where) {
  sim::PlantShape shape;
  if (!props.is_object()) return shape;
  for (const auto& [key, member] : detail::kShapeKeys) {
    if (!props.contains(key) || props[key].is_null()) continue;
    const json& v = props[key];
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() <= 0.0)
      throw InputError(file, where, std::string("properties.") + key + ": expected a positive number [m]");
    shape.*member = v.get<double>();
  }
  return shape;
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
  const std::string role = string_property(props, "type", file, where);
  const std::string block = string_property(props, "block", file, where);
  if (type == "LineString" && (role.empty() || role == "row")) {
    add_line(raw, g["coordinates"], block, file, where);
  } else if (type == "MultiLineString" && (role.empty() || role == "row")) {
    if (!g["coordinates"].is_array())
      throw InputError(file, where, "MultiLineString needs an array");
    for (const auto& part : g["coordinates"]) add_line(raw, part, block, file, where);
  } else if (type == "Point") {
    sim::PlantKind kind;
    if (detail::plant_kind(string_property(props, "kind", file, where), kind))
      raw.add_plant({position(g["coordinates"], file, where), kind, "", where,
                     plant_shape(props, file, where)},
                    file);
  }
}

}  // namespace

sim::RowLayout read_geojson_layout(const std::filesystem::path& file,
                                   const LayoutReadOptions& options) {
  const std::string name = file.string();
  const json doc =
      detail::parse_json_limited(detail::file_text(file), options.limits.max_json_depth, name);
  // (value("type", "") would throw a type error, without the file name, on a non-string type.)
  if (!doc.is_object() || !doc.contains("type") || doc["type"] != "FeatureCollection" ||
      !doc.contains("features") || !doc["features"].is_array())
    throw InputError(name, "", "not a GeoJSON FeatureCollection");
  RawLayout raw;
  raw.limits = options.limits;
  for (std::size_t i = 0; i < doc["features"].size(); ++i)
    read_feature(raw, doc["features"][i], name, "feature " + std::to_string(i));
  return detail::finish_layout(std::move(raw), file, options);
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
