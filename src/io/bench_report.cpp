// Markdown, JSON and SVG output of the benchmark tables.
#include "rownav/io/bench_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "rownav/io/plot.hpp"

namespace rownav::io {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error(file.string() + ": cannot write");
}

json table_json(const ResultTable& t) {
  json cols = json::array();
  for (const auto& c : t.label_columns) cols.push_back(c);
  for (const auto& c : t.value_columns) cols.push_back(c);
  json rows = json::array();
  for (const auto& r : t.rows) {
    json row = json::array();
    for (const auto& l : r.labels) row.push_back(l);
    for (const auto& v : r.values) row.push_back(v ? json(*v) : json(nullptr));
    rows.push_back(std::move(row));
  }
  return {{"key", t.key}, {"title", t.title}, {"columns", cols}, {"rows", rows}};
}

// Horizontal layout: one bar per row (labels joined), the value column on the y axis.
void write_bar_plot(const fs::path& file, const ResultTable& t) {
  const auto col = static_cast<std::size_t>(t.plot_column);
  std::vector<std::pair<std::string, double>> bars;
  for (const auto& r : t.rows) {
    std::string label;
    for (const auto& l : r.labels) label += (label.empty() ? "" : " / ") + l;
    if (r.values[col]) bars.emplace_back(label, *r.values[col]);
  }
  if (bars.empty()) return;
  double hi = 0.0;
  for (const auto& b : bars) hi = std::max(hi, b.second);
  hi = hi > 0 ? hi * 1.1 : 1.0;
  const int left = 260, top = 40, bar_h = 22, width = 760;
  const int height = top + 30 + bar_h * static_cast<int>(bars.size()) + 20;
  const auto canvas = make_canvas(file);
  Canvas& c = *canvas;
  const Eigen::AlignedBox2d plot(Eigen::Vector2d(left, top),
                                 Eigen::Vector2d(width - 40, height - 30));
  c.set_view_rect(Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(hi, 1)), plot, width,
                  height);
  const Color ink = Color::hex("#222222");
  c.text_px(Eigen::Vector2d(10, 18), t.title + ": " + t.value_columns[col], 13, ink);
  const Style bar{Color::hex("#1f77b4"), Color::hex("#1f77b4"), 0.0, true, false};
  for (std::size_t i = 0; i < bars.size(); ++i) {
    const double y = top + 10 + bar_h * static_cast<double>(i);
    const double x1 = left + (width - 40 - left) * bars[i].second / hi;
    c.rect_px(Eigen::Vector2d(left, y), Eigen::Vector2d(std::max(x1, left + 1.0), y + bar_h - 6),
              bar);
    c.text_px(Eigen::Vector2d(left - 6, y + bar_h / 2.0 - 3), bars[i].first, 11, ink, Align::right);
    c.text_px(Eigen::Vector2d(x1 + 4, y + bar_h / 2.0 - 3), format_value(bars[i].second), 11, ink);
  }
  c.line_px(Eigen::Vector2d(left, top + 5), Eigen::Vector2d(left, height - 25),
            Style{ink, ink, 1.0, false, false});
  c.save(file);
}

}  // namespace

std::string format_value(const std::optional<double>& v) {
  if (!v || !std::isfinite(*v)) return "n/a";
  if (*v == std::round(*v) && std::abs(*v) < 1e12) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f", *v);
    return buf;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", *v);
  return buf;
}

std::string tables_markdown(const std::string& scenario, const std::vector<ResultTable>& tables) {
  std::ostringstream md;
  md << "# rownav bench: " << scenario << "\n\n";
  if (tables.empty()) md << "No run has a summary.json yet.\n";
  for (const auto& t : tables) {
    md << "## " << t.title << "\n\n|";
    for (const auto& c : t.label_columns) md << " " << c << " |";
    for (const auto& c : t.value_columns) md << " " << c << " |";
    md << "\n|";
    for (std::size_t i = 0; i < t.label_columns.size() + t.value_columns.size(); ++i) md << "---|";
    md << "\n";
    for (const auto& r : t.rows) {
      md << "|";
      for (const auto& l : r.labels) md << " " << l << " |";
      for (const auto& v : r.values) md << " " << format_value(v) << " |";
      md << "\n";
    }
    const bool plotted =
        t.plot_column >= 0 && std::any_of(t.rows.begin(), t.rows.end(), [&](const ResultRow& r) {
          return r.values[static_cast<std::size_t>(t.plot_column)].has_value();
        });
    if (plotted) md << "\n![" << t.key << "](plots/" << t.key << ".svg)\n";
    md << "\n";
  }
  return md.str();
}

std::vector<fs::path> write_tables(const fs::path& out, const std::string& scenario,
                                   const std::vector<ResultTable>& tables) {
  fs::create_directories(out / "plots");
  std::vector<fs::path> written = {out / "tables.md", out / "tables.json"};
  write_text(written[0], tables_markdown(scenario, tables));
  json doc = {{"scenario", scenario}, {"tables", json::array()}};
  for (const auto& t : tables) doc["tables"].push_back(table_json(t));
  write_text(written[1], doc.dump(2) + "\n");
  for (const auto& t : tables) {
    if (t.plot_column < 0) continue;
    const fs::path svg = out / "plots" / (t.key + ".svg");
    write_bar_plot(svg, t);
    if (fs::exists(svg)) written.push_back(svg);
  }
  return written;
}

}  // namespace rownav::io
