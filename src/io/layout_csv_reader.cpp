// CSV layouts (format in layout_reader.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>

#include "layout_raw.hpp"
#include "rownav/io/csv.hpp"
#include "rownav/io/layout_reader.hpp"

namespace rownav::io {
namespace {

using detail::RawLayout;
using detail::RawRow;

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
  // Quoted and escaped: a cell may hold a '\r' or control bytes, and the error is one line.
  throw InputError(file, where, column + ": " + quote_for_message(cell) + " is not a number");
}

/// Column indices of a CSV header.
struct CsvColumns {
  int row = -1, x = -1, y = -1, kind = -1, block = -1;
  std::array<int, detail::kShapeKeys.size()> shape{-1, -1, -1, -1, -1, -1};  // optional sizes
  bool geographic = false;
  std::size_t count = 0;
};

/// Records `name` as a PlantShape column; false when it is none.
bool shape_column(CsvColumns& c, const std::string& name, int idx) {
  for (std::size_t k = 0; k < detail::kShapeKeys.size(); ++k)
    if (name == detail::kShapeKeys[k].first) return c.shape[k] = idx, true;
  return false;
}

/// The sizes of a plant line: empty cells stay NaN, others are positive numbers [m].
sim::PlantShape csv_shape(const CsvColumns& c, const std::vector<std::string>& cells,
                          const std::string& file, const std::string& where) {
  sim::PlantShape shape;
  for (std::size_t k = 0; k < detail::kShapeKeys.size(); ++k) {
    if (c.shape[k] < 0 || cells[static_cast<std::size_t>(c.shape[k])].empty()) continue;
    const char* name = detail::kShapeKeys[k].first;
    const double v = csv_number(cells[static_cast<std::size_t>(c.shape[k])], name, file, where);
    if (v <= 0.0) throw InputError(file, where, std::string(name) + ": must be > 0 [m]");
    shape.*detail::kShapeKeys[k].second = v;
  }
  return shape;
}

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
    else if (!shape_column(c, h, idx))
      throw InputError(file, where, "unknown column " + quote_for_message(h));
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
    if (it == raw.rows.end()) {
      raw.add_row(RawRow{{}, block, label, where, {}}, file);
      it = raw.rows.end() - 1;
    }
    if (it->block != block)
      throw InputError(file, where, "row " + quote_for_message(label) + " changes block");
    it->points.push_back(p);
    it->point_wheres.push_back(where);
  } else if (detail::plant_kind(kind, pk)) {
    raw.add_plant({p, pk, label, where, csv_shape(c, cells, file, where)}, file);
  } else {
    throw InputError(file, where,
                     "kind: unknown " + quote_for_message(kind) +
                         " (expected row, vine, tree, crop, post or end_post)");
  }
}

}  // namespace

sim::RowLayout read_csv_layout(const std::filesystem::path& file,
                               const LayoutReadOptions& options) {
  const std::string name = file.string();
  std::istringstream in(detail::file_text(file));
  RawLayout raw;
  raw.limits = options.limits;
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
      throw InputError(name, r.where,
                       "row " + quote_for_message(r.label) + " has fewer than 2 points");
  for (const auto& p : raw.plants)
    if (std::none_of(raw.rows.begin(), raw.rows.end(),
                     [&](auto& r) { return r.label == p.row_label; }))
      throw InputError(name, p.where,
                       "row " + quote_for_message(p.row_label) + " has no row points");
  return detail::finish_layout(std::move(raw), file, options);
}

}  // namespace rownav::io
