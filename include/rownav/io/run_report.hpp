#pragma once
/// @file run_report.hpp Writes a closed-loop run's outputs into a directory: summary.json
/// (docs/summary_json.md), report.html (self-contained, inline SVGs), top_view.svg and
/// trajectory.csv. Everything goes to DIR.partial first, renamed to DIR on success.
#include <filesystem>
#include <string>

#include "rownav/io/closed_loop_runner.hpp"
#include "rownav/io/run_metrics.hpp"

namespace rownav::io {

/// Names of the set-up, for the summary.
struct RunNames {
  std::string field, robot, sensor, mission, detector, tracker, controller;
  std::uint64_t seed = 1;
};

/// summary.json content (pretty-printed JSON text).
std::string summary_json(const RunSummary& s, const RunNames& names);

/// Writes summary.json, report.html, top_view.svg, trajectory.csv into `out` (replaced).
/// Throws std::runtime_error when the directory cannot be written.
void write_run_report(const std::filesystem::path& out, const RunResult& run,
                      const RunSummary& summary, const RunNames& names, const sim::Field& field);

}  // namespace rownav::io
