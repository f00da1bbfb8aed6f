#pragma once
/// @file run_mission.hpp The closed-loop mission shared by `rownav run` and `rownav demo`.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "rownav/navigate/row_end_poles.hpp"

namespace rownav::app {

/// Options of a closed-loop run (file paths as given on the command line).
struct RunArgs {
  std::filesystem::path field, robot, mission, out;
  /// config/detect/<crop>.yaml and config/navigate/<crop>.yaml live here
  std::filesystem::path config_dir = "config";
  std::optional<std::filesystem::path> sensor, detect_config, track_config, control_config,
      nav_config;
  /// a YAML file with a `faults:` section (sim::FaultsConfig), replacing the sensors' faults
  std::optional<std::filesystem::path> faults;
  std::string detector;  ///< empty: the detection config's `detector:` key, else hough_skew
  std::string tracker = "model_filter";
  std::string controller = "stanley";
  std::optional<navigate::RowEndPolicy> row_end_policy;  ///< overrides the navigator config
  /// map stage (issue 12): `--place` turns it on over the navigation config; labels `truth`
  /// (sim::TruthLabeller, with the false-positive / false-negative rates), `geometric` or
  /// `camera` (simulated camera + excess-green boxes + vision::CameraLabeller)
  bool place = false;
  std::string labels = "truth";
  double label_fp = 0.0, label_fn = 0.0;  ///< [-] truth labeller error rates
  std::uint64_t seed = 1;
  double time_limit = 1800.0;  ///< [s] simulated
  std::optional<double> lead_in;  ///< [m] start before the first corridor (runner default)
  double start_offset = 0.0;      ///< [m] start left (+) of the corridor centre line
  double start_yaw_deg = 0.0;     ///< [deg] start heading from the corridor direction (left +)
  bool quiet = false;
  bool overwrite = false;  ///< replace `out` when it is an earlier rownav output
};

/// Runs the mission, prints a short summary on stdout, writes the report into args.out.
/// Returns true when the mission succeeded. Throws (InputError, invalid_argument) on bad input.
bool run_mission(const RunArgs& args);

}  // namespace rownav::app
