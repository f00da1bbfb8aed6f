#pragma once
/// @file fault_metrics.hpp How a closed-loop run answered the simulator's faults (issue 13): per
/// enabled fault, the time from its start to a zero command and to the robot standing still,
/// the time from its end to moving again, and for the person the clearance kept; per run,
/// whether the robot ever left the field.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rownav/io/closed_loop_runner.hpp"
#include "rownav/io/run_metrics.hpp"
#include "rownav/sim/fault_config.hpp"

namespace rownav::io {

/// One fault's window and what the stack did about it.
struct FaultOutcome {
  std::string fault;          ///< FaultsConfig key, e.g. "lidar_dropout"
  double start = 0.0, end = 0.0;  ///< [s] the window
  std::string state_at_start;     ///< navigator state when the fault began
  /// [s] from start to the first zero command (watchdog, safe stop or a controller's zero)
  std::optional<double> zero_after;
  std::optional<double> halted_after;   ///< [s] from start until the true speed is ~0
  /// [s] from the window's end until the robot is commanded to move again after the zero
  /// (negative: moving again while the fault still acts); nullopt: never (a safe stop ends the
  /// run) or never stopped
  std::optional<double> resumed_after;
  double min_clearance = 0.0;  ///< [m] person only: nearest the footprint came (inf otherwise)
};

/// A run's answer to its faults.
struct FaultReport {
  std::vector<FaultOutcome> faults;  ///< enabled faults, in FaultsConfig order
  bool left_field = false;           ///< some ground-truth sample was outside the field
  double min_person_clearance = 0.0; ///< [m] inf without a person
};

/// Measures `run` against the enabled faults of `config` (samples at 20 Hz, events exact).
FaultReport fault_report(const RunResult& run, const sim::FaultsConfig& config);

/// Writes `faults.json` (the report plus the run's success, stop reason, plants crushed and
/// collision) into `dir`.
void write_fault_report(const std::filesystem::path& dir, const FaultReport& report,
                        const RunSummary& summary);

/// One line per fault for the terminal.
std::string describe(const FaultReport& report);

}  // namespace rownav::io
