// The regression gate: metrics over all runs against bench/quick_baseline.json.
#include "json_file.hpp"
#include "rownav/io/bench_baseline.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "rownav/io/bench_report.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

std::optional<double> sum_of(const std::vector<const RunSummary*>& runs, const std::string& key) {
  std::optional<double> sum;
  for (const auto* r : runs)
    if (const auto v = r->get(key)) sum = sum.value_or(0.0) + *v;
  return sum;
}

BaselineMetric read_metric(const json& j, const std::string& file, const std::string& name) {
  if (!j.is_object()) throw InputError(file, "", "metrics." + name + ": expected an object");
  BaselineMetric m;
  for (const auto& [key, v] : j.items()) {
    const std::string at = "metrics." + name + "." + key;
    if (key == "value" && (v.is_null() || v.is_number()))
      m.value = v.is_null() ? std::nullopt : std::optional<double>(v.get<double>());
    else if (key == "better" && v.is_string() && (v == "higher" || v == "lower"))
      m.higher_is_better = v == "higher";
    else if (key == "tolerance" && v.is_number() && v.get<double>() >= 0)
      m.tolerance = v.get<double>();
    else if (key == "relative_tolerance" && v.is_number() && v.get<double>() >= 0)
      m.relative_tolerance = v.get<double>();
    else if (key == "value" || key == "better" || key == "tolerance" || key == "relative_tolerance")
      throw InputError(file, "", at + ": bad value " + v.dump());
    else
      throw InputError(file, "",
                       at + ": unknown key (valid: value, better, tolerance, "
                            "relative_tolerance)");
  }
  return m;
}

}  // namespace

std::map<std::string, std::optional<double>> gate_metrics(const std::vector<CellResult>& runs) {
  std::vector<const RunSummary*> s;
  double failed = 0;
  for (const auto& r : runs) {
    if (r.summary)
      s.push_back(&*r.summary);
    else
      ++failed;
  }
  std::optional<double> success;
  if (!s.empty()) success = 100.0 * sum_of(s, "success").value_or(0.0) / double(s.size());
  return {{"success_rate", success},
          {"in_row_mean_displacement", aggregate(s, "in_row_mean_displacement", Aggregate::mean)},
          {"in_row_max_displacement", aggregate(s, "in_row_max_displacement", Aggregate::max)},
          {"plants_crushed", sum_of(s, "plants_crushed")},
          {"correct_entries", sum_of(s, "correct_entries")},
          {"frame_latency_median_ms", aggregate(s, "frame_latency_median_ms", Aggregate::median)},
          {"failed_cells", failed}};
}

Baseline read_baseline(const fs::path& file) {
  const json j = detail::read_json_file(file);
  if (!j.is_object() || !j.contains("metrics") || !j["metrics"].is_object())
    throw InputError(file.string(), "", "expected an object with \"metrics\": {...}");
  Baseline b;
  if (j.contains("scenario") && j["scenario"].is_string()) b.scenario = j["scenario"];
  for (const auto& [name, m] : j["metrics"].items())
    b.metrics[name] = read_metric(m, file.string(), name);
  return b;
}

void write_baseline(const fs::path& file, const Baseline& b) {
  json metrics = json::object();
  for (const auto& [name, m] : b.metrics)
    metrics[name] = {{"value", m.value ? json(*m.value) : json(nullptr)},
                     {"better", m.higher_is_better ? "higher" : "lower"},
                     {"tolerance", m.tolerance},
                     {"relative_tolerance", m.relative_tolerance}};
  std::ofstream out(file);
  out << json{{"scenario", b.scenario}, {"metrics", metrics}}.dump(2) << "\n";
  if (!out) throw std::runtime_error(file.string() + ": cannot write");
}

std::vector<std::string> check_baseline(const Baseline& baseline,
                                        const std::map<std::string, std::optional<double>>& now) {
  std::vector<std::string> out;
  for (const auto& [name, m] : baseline.metrics) {
    if (!m.value) continue;
    const auto it = now.find(name);
    const std::optional<double> v = it == now.end() ? std::nullopt : it->second;
    const double tol = m.tolerance + m.relative_tolerance * std::abs(*m.value);
    const bool worse = !v || (m.higher_is_better ? *v < *m.value - tol : *v > *m.value + tol);
    if (worse)
      out.push_back(name + ": value " + format_value(v) + ", baseline " + format_value(m.value) +
                    ", tolerance " + format_value(tol) +
                    (m.higher_is_better ? " (higher is better)" : " (lower is better)"));
  }
  return out;
}

Baseline updated_baseline(Baseline baseline,
                          const std::map<std::string, std::optional<double>>& now) {
  for (const auto& [name, v] : now) {
    auto [it, added] = baseline.metrics.try_emplace(name);
    if (added)
      it->second.higher_is_better =
          name.size() > 5 && (name.ends_with("_rate") || name.starts_with("correct_"));
    it->second.value = v;
  }
  return baseline;
}

}  // namespace rownav::io
