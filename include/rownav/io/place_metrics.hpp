#pragma once
/// @file place_metrics.hpp Metrics of the map stage in a closed-loop run (issue 12): place
/// accuracy per LiDAR frame against the simulator's true place, and the validated key
/// locations' error to the true lane ends (Emmi 2021, 002_806e72d300173f73.txt, Table 4:
/// state accuracy, key location distance error).
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "rownav/io/closed_loop_runner.hpp"
#include "rownav/sim/field_truth.hpp"

namespace rownav::io {

/// One validated key location in the world and its error.
struct KeyLocationMetric {
  std::string from, to;  ///< places of the transition (entry: to lane / alley; exit: from it)
  Eigen::Vector2d world = Eigen::Vector2d::Zero();  ///< [m]
  double error = 0.0;  ///< [m] to the nearest end of a true corridor centre line
};

/// The map stage's metrics; empty / nullopt when it was off.
struct PlaceMetrics {
  int frames = 0;                      ///< LiDAR frames with an estimate
  std::optional<double> accuracy;      ///< [-] frames whose validated place is the true one
  std::vector<KeyLocationMetric> keys;
  std::optional<double> key_error_median, key_error_max;  ///< [m]
};

/// The simulator's place in the map stage's terms: `outside` (beyond the headland band) is
/// headland too (Emmi 2021: the headland is the open area around the rows).
map::Place map_place(sim::Place p);

/// A key location is the lane centre at a row end (Emmi 2021 Fig. 3): its error is the
/// distance to the nearest end of a true corridor centre line of `block`.
PlaceMetrics place_metrics(const RunResult& run, const sim::FieldTruth& truth, int block);

}  // namespace rownav::io
