#pragma once
/// @file bench_runner.hpp Runs benchmark cells as child processes (`RUNNER run <options> --out
/// OUT/runs/<id>`), several at a time, resumably: a cell whose folder holds a summary.json is not
/// run again (any other content of its folder and <id>.partial is removed before it runs). Each
/// child's stdout and stderr go to OUT/runs/<id>/log.txt (after the command line). One progress
/// line per finished cell on the progress stream. SIGINT / SIGTERM stop launching, terminate the
/// running children and wait for them.
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "rownav/io/bench_matrix.hpp"

namespace rownav::io {

/// How to run the cells.
struct BenchRunnerOptions {
  std::filesystem::path runner;         ///< executable, called as `runner run <cell options>`
  int jobs = 1;                         ///< [-] cells at a time (>= 1)
  std::ostream* progress = &std::cerr;  ///< progress lines (nullptr: none)
};

/// What became of a cell.
enum class CellStatus {
  ran,      ///< the runner wrote summary.json (mission success or failure)
  resumed,  ///< summary.json was there already: not run
  failed,   ///< no summary.json after the run (bad input, crash, killed)
  not_run,  ///< interrupted before it finished
};

/// One cell's outcome.
struct CellOutcome {
  std::string id;
  CellStatus status = CellStatus::not_run;
  std::string detail;  ///< "exit 2", "killed by signal 9", ... for failures
};

/// The outcome of run_cells.
struct BenchRunResult {
  std::vector<CellOutcome> cells;  ///< in the cells' order
  bool interrupted = false;        ///< a stop signal arrived
  /// Cells with status `s`.
  int count(CellStatus s) const;
};

/// Runs (or resumes) every cell. Never throws for a failing child; throws std::runtime_error
/// when a cell folder cannot be created or the runner cannot be started at all.
BenchRunResult run_cells(const std::vector<BenchCell>& cells, const std::filesystem::path& out,
                         const BenchRunnerOptions& options);

}  // namespace rownav::io
