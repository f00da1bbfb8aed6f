#pragma once
/// @file bench_matrix.hpp Expansion of a benchmark scenario into cells: one closed-loop run each,
/// with a stable id (readable slug + hash of every run setting) naming its folder OUT/runs/<id>/.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "rownav/io/bench_scenario.hpp"

namespace rownav::io {

/// Detector name meaning "the crop's default detector" (no `--detector` passed to the run).
inline constexpr std::string_view kCropDetector = "default";

/// One run of the matrix.
struct BenchCell {
  std::string id;                     ///< stable: same settings, same id (folder name)
  std::vector<std::string> matrices;  ///< matrices that contain this run (identical runs merge)
  std::vector<BenchTable> tables;     ///< tables it feeds (union over its matrices)
  std::filesystem::path field, robot, sensor, mission;  ///< files (resolved against the root);
                                                        ///< `field` may be a zoo reference
  std::string detector, tracker, controller;
  std::string row_end_policy;  ///< empty: the runner's default
  std::uint64_t seed = 0;
  double time_limit = 0.0;              ///< [s]
  std::vector<std::string> extra_args;  ///< appended to the run's options

  /// File stem of `field`, or the zoo field's name (the field's label in tables).
  std::string field_name() const;
  /// "detector+tracker+controller" (the pipeline's label in tables).
  std::string pipeline() const;
  /// True when the cell feeds table `t`.
  bool feeds(BenchTable t) const;
  /// The options of `rownav run` for this cell writing into `out_dir`.
  std::vector<std::string> run_args(const std::filesystem::path& out_dir) const;
};

/// The cells of every matrix (cartesian product, in file order: fields, robots, sensors,
/// missions, detectors, trackers, controllers, row-end policies, seeds); runs with identical
/// settings appear once.
std::vector<BenchCell> expand_scenario(const BenchScenario& scenario);

/// OUT/runs/<id>.
std::filesystem::path cell_dir(const std::filesystem::path& out, const BenchCell& cell);

}  // namespace rownav::io
