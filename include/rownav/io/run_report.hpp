#pragma once
/// @file run_report.hpp Writes a closed-loop run's outputs into a directory: summary.json
/// (docs/summary_json.md), report.html (self-contained, inline SVGs), top_view.svg and
/// trajectory.csv. The caller owns the directory: an io::OutputDir's staging directory, moved
/// into place when everything is written.
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

/// Writes summary.json, report.html, top_view.{svg,png}, the plots and trajectory.csv into `dir`
/// (created when missing; nothing else in it is touched). Throws std::runtime_error when the
/// directory cannot be written.
void write_run_report(const std::filesystem::path& dir, const RunResult& run,
                      const RunSummary& summary, const RunNames& names, const sim::Field& field);

}  // namespace rownav::io
