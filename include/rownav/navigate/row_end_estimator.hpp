#pragma once
/// @file row_end_estimator.hpp Where the corridor being left ends, and the row spacing, from the
/// tracked rows while the robot drives out (Bertoglio 2023, 003_25dc0df51a1e5faf.txt sec. II-C:
/// the end-row points; Table I's row width). Kept in the odom frame: the latest frames give the
/// ends relative to the robot with the least odometry drift, a median of a few drops outliers.
#include <Eigen/Core>
#include <deque>
#include <optional>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/line2.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/track/row_tracker.hpp"

namespace rownav::navigate {

/// Row-end estimator parameters.
struct RowEndEstimatorConfig {
  int frames = 5;  ///< [frames] row-end point = median of the latest per-frame estimates (rownav)
  /// [m] a row's far end counts only when nearer than this (beyond it the extent is the sensor's
  /// reach, not the row's end: an OS1-16's canopy returns thin out at ~7 m; rownav)
  double max_range = 7.0;
  int min_support = 3;      ///< [points] a row seen by fewer points gives no end (rownav)
  int spacing_window = 50;  ///< [frames] running mean of the tracker's spacing (~5 s at 10 Hz)
  /// [m] the row-end estimate is settled once the robot has driven this far while the estimated
  /// end point stayed within settle_tolerance of where it was (odom): a real end stands still,
  /// an extent cut by the sensor's reach or by an occluder moves along with the robot (rownav)
  double settle_distance = 1.0;
  double settle_tolerance = 0.3;  ///< [m] (rownav)
  /// [deg] a row's end counts only when the row runs within this angle of the corridor's
  /// centre line: past the ends the tracker can hold clutter lying across the headland, whose
  /// far end would push the exit on (rownav)
  double row_angle_gate_deg = 10.0;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("frames", s.frames);
    v("max_range", s.max_range);
    v("min_support", s.min_support);
    v("spacing_window", s.spacing_window);
    v("settle_distance", s.settle_distance);
    v("settle_tolerance", s.settle_tolerance);
    v("row_angle_gate_deg", s.row_angle_gate_deg);
  }
  void validate() const {
    core::check_positive(frames, "frames");
    core::check_positive(max_range, "max_range");
    core::check_positive(min_support, "min_support");
    core::check_positive(spacing_window, "spacing_window");
    core::check_non_negative(settle_distance, "settle_distance");
    core::check_positive(settle_tolerance, "settle_tolerance");
    // (0, 90]: past 90 deg the sine of the gate shrinks again (as row_end_poles' max_line_angle)
    core::check_positive(row_angle_gate_deg, "row_angle_gate_deg");
    core::check_range(row_angle_gate_deg, 0.0, 90.0, "row_angle_gate_deg");
  }
};

/// Row ends and spacing of the corridor being served. Never throws.
class RowEndEstimator {
 public:
  explicit RowEndEstimator(const RowEndEstimatorConfig& config = {}) : config_(config) {}

  /// One tracked frame at pose T (odom). Only rows observed in this frame (`frame_stamp`) count:
  /// a coasting row keeps an older frame's extent, in that frame's base.
  void update(const track::RowTracking& t, const core::Pose2& T, double frame_stamp);
  /// The exit corridor's centre line (odom, oriented forward), once tracked.
  const std::optional<core::Line2>& centre() const { return centre_; }
  /// [m] row end along centre(): the farther of the left and right ends (the exit must clear
  /// both rows), once seen or set.
  const std::optional<double>& end_arc() const { return end_arc_; }
  void set_end_arc(double arc) { end_arc_ = arc; }
  /// [m] the estimated end's distance ahead of the robot along centre() when that end has
  /// settled (stood still in odom while the robot drove settle_distance), else nullopt.
  std::optional<double> settled_end_ahead() const;
  const std::optional<Eigen::Vector2d>& left_end() const { return left_end_; }
  const std::optional<Eigen::Vector2d>& right_end() const { return right_end_; }
  /// [m] row spacing: running mean of the tracker's, else the distance between the two ends,
  /// else 0 (unknown).
  double spacing() const;
  /// A new corridor: forgets the centre line and the ends (the spacing is kept).
  void reset();

 private:
  Eigen::Vector2d recent_median(std::deque<Eigen::Vector2d>& recent, const Eigen::Vector2d& p);

  RowEndEstimatorConfig config_;
  std::optional<core::Line2> centre_;
  std::optional<Eigen::Vector2d> left_end_, right_end_;
  std::deque<Eigen::Vector2d> left_ends_, right_ends_;
  std::optional<double> end_arc_;
  std::optional<Eigen::Vector2d> anchor_end_;  // the end point when it last moved (odom)
  Eigen::Vector2d anchor_robot_ = Eigen::Vector2d::Zero(), robot_ = Eigen::Vector2d::Zero();
  double spacing_ = 0.0;
  int spacing_n_ = 0;
};

}  // namespace rownav::navigate
