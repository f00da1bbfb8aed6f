#pragma once
/// @file bench_tables.hpp The paper tables of `rownav bench`, aggregated from the cells'
/// summary.json files (docs/summary_json.md). A value that no run measured is n/a (nullopt).
///
/// Aggregation over the runs of a table row (runs without summary.json are left out; `runs`
/// counts the others): rates are percentages of runs; "mean" is the mean over runs of the run's
/// value, "max" / "min" the extreme over runs of the run's max / min, "median" the median over
/// runs.
/// - 004 Tables 1-3 (Malavazi 2018), one table per field (weed level), a row per detector x
///   filtered (a tracker) / unfiltered (tracker `none`): success [%], success without crushed
///   plants [%], path-length ratio mean / max / min;
/// - 003 Table I (Bertoglio 2023), a row per field x robot file x pipeline (the robot file
///   tells the protocol's speeds apart): success [%], top speed, centre displacement mean / max,
///   corridor width mean / max / min; Table II, a row per field x robot file x row-end policy:
///   row-end point error mean / max;
/// - 000 Tables 1-2 (Nehme 2021), one table per field: lateral RMSE per corridor (per_corridor),
///   a column per pipeline, last row the run's whole in-row RMSE;
/// - 001 Tables 2-3 (Lan 2021), a row per field x pipeline: line slope / intercept error
///   mean / std, tracked lateral / heading error RMSE / max;
/// - timing, a row per pipeline: per-frame latency median (median of the runs' medians) and
///   p99 (max over runs), simulated-to-wall time ratio (sum over runs).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rownav/io/bench_matrix.hpp"
#include "rownav/io/bench_summary.hpp"

namespace rownav::io {

/// A cell and its summary (nullopt when the run left none). Not io::RunResult
/// (closed_loop_runner.hpp): two classes of one name in one namespace broke the tests linking both
/// (ODR).
struct CellResult {
  BenchCell cell;
  std::optional<RunSummary> summary;
};

/// One row: its label cells, then its values.
struct ResultRow {
  std::vector<std::string> labels;
  std::vector<std::optional<double>> values;
};

/// One output table.
struct ResultTable {
  std::string key;    ///< file-name-safe id, e.g. "malavazi_004_vineyard_weeds_some"
  std::string title;  ///< heading in tables.md
  std::vector<std::string> label_columns, value_columns;
  std::vector<ResultRow> rows;
  int plot_column = -1;  ///< value column drawn as a bar plot (-1: none)
};

/// Reads OUT/runs/<id>/summary.json of every cell; a malformed one counts as missing and is
/// reported on `warnings` (one line each).
std::vector<CellResult> collect_results(const std::vector<BenchCell>& cells,
                                        const std::filesystem::path& out,
                                        std::vector<std::string>* warnings = nullptr);

/// The tables fed by the runs, in the order of BenchTable, rows in the order of first
/// appearance. Tables without any run are left out.
std::vector<ResultTable> build_tables(const std::vector<CellResult>& runs);

/// Mean, max, min, median or sum of `key` over the runs that have it; nullopt when none has.
enum class Aggregate { mean, max, min, median, sum };
std::optional<double> aggregate(const std::vector<const RunSummary*>& runs, const std::string& key,
                                Aggregate how);

}  // namespace rownav::io
