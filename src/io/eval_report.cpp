// Markdown tables and JSON of the detection accuracy results.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "rownav/io/detection_eval.hpp"

namespace rownav::io {

namespace {

std::string fmt(double v, const char* format) {
  if (!std::isfinite(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// "median / p95" with a unit scale (m -> cm).
std::string stat_cell(const Stat& s, double scale) {
  if (s.n == 0) return "-";
  return fmt(s.median * scale, "%.1f") + " / " + fmt(s.p95 * scale, "%.1f");
}

std::string percent(double rate) {
  return fmt(100.0 * rate, "%.0f") + " %";
}

nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}

nlohmann::json stat_json(const Stat& s) {
  return {{"n", s.n}, {"median", number(s.median)}, {"p95", number(s.p95)}};
}

}  // namespace

std::string scenario_table_markdown(const std::vector<ScenarioEval>& results) {
  std::string out =
      "| detector | scenario | LiDAR | frames | heading error [deg] median / p95 | lateral "
      "error [cm] median / p95 | corridor rows output | detection rate | false rows / frame | time "
      "[ms / frame] |\n|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& r : results) {
    out += "| " + r.detector + " | " + r.scenario + " | " + r.lidar + " | " +
           std::to_string(r.frames) + " | " + stat_cell(r.heading_deg, 1.0) + " | " +
           stat_cell(r.lateral_m, 100.0) + (r.corridor_only ? " (centre)" : "") + " | " +
           percent(r.frames ? r.lateral_m.n / (r.corridor_only ? 1.0 : 2.0) / r.frames : 0.0) +
           " | " + percent(r.detection_rate) + " | " + fmt(r.false_rows_per_frame, "%.2f") + " | " +
           fmt(r.ms_per_frame, "%.2f") + " |\n";
  }
  return out;
}

std::string corn_table_markdown(const std::vector<CornEval>& results) {
  std::string out =
      "| detector | frames | lateral error at 0.5 m [cm] median / p95 | lateral error at 1.5 m "
      "[cm] median / p95 | heading error [deg] median / p95 | row heading error [deg] median / p95 "
      "| lines detected (within 0.2 m) | lines output | time [ms / frame] |\n"
      "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& r : results) {
    out += "| " + r.detector + " | " + std::to_string(r.frames) + " | " +
           stat_cell(r.lateral_05_m, 100.0) + " | " + stat_cell(r.lateral_15_m, 100.0) + " | " +
           stat_cell(r.heading_deg, 1.0) + " | " + stat_cell(r.row_heading_deg, 1.0) + " | " +
           percent(r.detection_rate) + " | " + percent(r.output_rate) + " | " +
           fmt(r.ms_per_frame, "%.3f") + " |\n";
  }
  return out;
}

std::string eval_json(const std::vector<ScenarioEval>& simulated,
                      const std::vector<CornEval>& corn) {
  nlohmann::json doc = {{"simulated", nlohmann::json::array()}, {"corn", nlohmann::json::array()}};
  for (const auto& r : simulated)
    doc["simulated"].push_back({{"detector", r.detector},
                                {"scenario", r.scenario},
                                {"lidar", r.lidar},
                                {"frames", r.frames},
                                {"corridor_only", r.corridor_only},
                                {"heading_error_deg", stat_json(r.heading_deg)},
                                {"lateral_error_m", stat_json(r.lateral_m)},
                                {"detection_rate", number(r.detection_rate)},
                                {"false_rows_per_frame", number(r.false_rows_per_frame)},
                                {"ms_per_frame", number(r.ms_per_frame)}});
  for (const auto& r : corn)
    doc["corn"].push_back({{"detector", r.detector},
                           {"frames", r.frames},
                           {"lines", r.lines},
                           {"lateral_error_0_5_m", stat_json(r.lateral_05_m)},
                           {"lateral_error_1_5_m", stat_json(r.lateral_15_m)},
                           {"heading_error_deg", stat_json(r.heading_deg)},
                           {"row_heading_error_deg", stat_json(r.row_heading_deg)},
                           {"detection_rate", number(r.detection_rate)},
                           {"output_rate", number(r.output_rate)},
                           {"ms_per_frame", number(r.ms_per_frame)}});
  return doc.dump(2) + "\n";
}

void write_eval_json(const std::filesystem::path& file, const std::vector<ScenarioEval>& simulated,
                     const std::vector<CornEval>& corn) {
  std::ofstream out(file, std::ios::binary);
  out << eval_json(simulated, corn);
  if (!out) throw std::runtime_error(file.string() + ": cannot write");
}

}  // namespace rownav::io
