#pragma once
/// @file run_metrics.hpp Metrics of a closed-loop run against the ground truth: the keys of
/// docs/summary_json.md (Bertoglio 2023 Table I displacement / row width, Table II row-end
/// error; Malavazi 2018 eq. (7) path-length ratio).
#include <optional>
#include <string>
#include <vector>

#include "rownav/io/closed_loop_runner.hpp"
#include "rownav/io/place_metrics.hpp"
#include "rownav/sim/field_truth.hpp"

namespace rownav::io {

/// The q-quantile (0..1) of `v` by nearest rank (index round(q (n - 1))); nullopt when empty.
std::optional<double> percentile(std::vector<double> v, double q);

/// Metrics of one served corridor.
struct CorridorMetrics {
  int corridor = -1;  ///< true corridor index
  double lateral_rmse = 0.0, mean_displacement = 0.0, max_displacement = 0.0;  ///< [m]
  double path_length_ratio = 1.0;  ///< 004 eq. (7): driven / centre-line length covered
  double heading_rmse_deg = 0.0;   ///< [deg]
  double length = 0.0;             ///< [m] centre-line length covered
};

/// One row end the stack estimated, against the nearest true row end of the block (the row's
/// last plant or end post): row_ends.csv.
struct RowEndRecord {
  Eigen::Vector2d estimate = Eigen::Vector2d::Zero();  ///< [m] world frame
  Eigen::Vector2d truth = Eigen::Vector2d::Zero();     ///< [m] world frame
  double error = 0.0;                                  ///< [m] distance between the two
  double along = 0.0;   ///< [m] + past the true end (into the headland), - short of it
  double across = 0.0;  ///< [m] beside the row's line, + to the left looking out of the row
};

/// Summary of a run; std::nullopt where a value cannot be measured (null in JSON).
struct RunSummary {
  bool success = false, mission_done = false, safe_stop = false, collision = false;
  std::string stop_reason;
  int corridors_planned = 0, corridors_served = 0, turns = 0, correct_entries = 0,
      wrong_entries = 0, plants_crushed = 0, tracking_lost_in_row = 0;
  bool corridors_in_order = false;
  std::optional<double> in_row_mean_displacement, in_row_max_displacement, in_row_lateral_rmse,
      in_row_heading_rmse_deg;
  std::optional<double> path_length_ratio_mean, path_length_ratio_max, path_length_ratio_min;
  std::optional<double> corridor_width_mean, corridor_width_max, corridor_width_min;
  std::optional<double> row_end_error_mean, row_end_error_max;
  /// [m] mean signed offset of the estimated row ends along their rows: + past the true end
  /// (into the headland), - short of it (the true end = the row's last plant or end post)
  std::optional<double> row_end_along_mean;
  std::vector<RowEndRecord> row_ends;  ///< each estimated row end (row_ends.csv, not in JSON)
  /// [m] 003 Table II: in each turn frame, each true row end (end post, else last plant)
  /// against the nearest of the frame's row-end points (NavCommand::row_end_points), when one
  /// lies within half the distance between neighbouring true ends (turn_row_end_points: those
  /// pole sightings); turn_row_end_spurious: the points farther than that from every true end
  std::optional<double> turn_row_end_error_mean, turn_row_end_error_max, turn_row_end_error_min;
  int turn_row_end_points = 0, turn_row_end_spurious = 0;
  std::optional<double> frame_latency_median_ms, frame_latency_p99_ms;
  std::optional<double> track_lateral_error_rmse, track_lateral_error_max;
  std::optional<double> track_heading_error_rmse_deg, track_heading_error_max_deg;
  std::optional<double> line_slope_error_mean, line_slope_error_std;
  std::optional<double> line_intercept_error_mean, line_intercept_error_std;
  double sim_time = 0.0, wall_time = 0.0, distance = 0.0;
  /// [m/s] the highest true forward speed of the run (003 sec. III: up to 2 m/s in simulation)
  double speed_max = 0.0;
  /// [-] the odometry's alpha at the end of the run (Bertoglio 2023 eq. (2)), and how many
  /// straight stretches measured it (0: not estimated, the robot file's or the nominal one)
  double odometry_alpha = 1.0;
  int odometry_scale_samples = 0;
  std::vector<CorridorMetrics> per_corridor;
  std::vector<CrushRecord> crushes;  ///< where each crushed plant was (summary.json `crushed`)
  PlaceMetrics place;                ///< the map stage (issue 12); empty when it was off
};

/// Path-length ratio of 004 eq. (7) for a driven polyline against a reference polyline: driven
/// length / length of the reference between the projections of the driven ends (>= 1 for a
/// path that wanders). nullopt when the covered reference length is < 1 m.
std::optional<double> path_length_ratio(const std::vector<Eigen::Vector2d>& driven,
                                        const std::vector<Eigen::Vector2d>& reference);

/// Computes every metric of a run; `block` is the mission's block.
RunSummary summarize(const RunResult& run, const sim::FieldTruth& truth, int block = 0);

}  // namespace rownav::io
