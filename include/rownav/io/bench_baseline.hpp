#pragma once
/// @file bench_baseline.hpp The regression gate of `rownav bench --quick`: metrics over all runs
/// compared against a stored baseline (bench/quick_baseline.json) with per-metric tolerances.
///
/// Baseline file: {"scenario": "...", "metrics": {"<name>": {"value": number | null,
/// "better": "higher" | "lower", "tolerance": abs, "relative_tolerance": fraction}}}.
/// A metric regresses when it is worse than value by more than tolerance + relative_tolerance x
/// |value|, or is n/a while the baseline has a value. A null baseline value is not checked.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rownav/io/bench_tables.hpp"

namespace rownav::io {

/// One gated metric.
struct BaselineMetric {
  std::optional<double> value;      ///< null: not measured yet (not checked)
  bool higher_is_better = false;    ///< "better": "higher" / "lower"
  double tolerance = 0.0;           ///< absolute
  double relative_tolerance = 0.0;  ///< fraction of |value|
};

/// A baseline file.
struct Baseline {
  std::string scenario;
  std::map<std::string, BaselineMetric> metrics;
};

/// The gated metrics over the runs with a summary: success_rate [%], in_row_mean_displacement
/// (mean), in_row_max_displacement (max), plants_crushed (sum), correct_entries (sum),
/// frame_latency_median_ms (median), failed_cells (cells without summary.json).
std::map<std::string, std::optional<double>> gate_metrics(const std::vector<CellResult>& runs);

/// Reads a baseline; InputError (one line) when missing or malformed.
Baseline read_baseline(const std::filesystem::path& file);
/// Writes a baseline (2-space JSON).
void write_baseline(const std::filesystem::path& file, const Baseline& baseline);

/// One line per regressed metric: "name: value V, baseline B, tolerance T (higher is better)".
std::vector<std::string> check_baseline(const Baseline& baseline,
                                        const std::map<std::string, std::optional<double>>& now);

/// The baseline with every metric's value replaced by `now` (tolerances kept; metrics of `now`
/// not in the baseline are added with zero tolerance, lower is better unless named *_rate or
/// correct_*).
Baseline updated_baseline(Baseline baseline,
                          const std::map<std::string, std::optional<double>>& now);

}  // namespace rownav::io
