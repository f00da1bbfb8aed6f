#pragma once
/// @file canopy_reach.hpp How far the followed rows' own canopy reaches into the corridor,
/// measured beside and behind the robot, so that the obstacle stop and the slow-down do not take
/// the rows' shoots, leaves and crowns at the robot's flanks for an obstacle (issue 10: in rows
/// narrower than the robot plus its canopy, vine shoots protruding 0.3 m and orchard crowns
/// reach into the footprint's edge; 9 of the zoo's 26 obstacle stops were in a row, points at
/// |y| 0.2-0.3 m of a 0.6 m wide robot, with no collision to come). The same reasoning as the
/// ground cover (ground_cover.hpp): what the robot has just driven beside is the row, and an
/// object ahead that reaches no further into the corridor than that is the row too. Anything
/// reaching further in, or deeper into the footprint than max_intrusion, still stops the robot.
#include <Eigen/Core>
#include <deque>
#include <limits>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/line2.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/preprocess/ground.hpp"

namespace rownav::navigate {

/// Canopy reach estimate parameters.
struct CanopyReachConfig {
  bool enabled = true;  ///< false: every point of the obstacle band counts (before issue 10)
  /// [m] region from this far behind the base origin to the robot's front: the canopy just
  /// driven beside (rownav; the ground cover's region, ground_cover.hpp)
  double behind = 4.0;
  /// [-] of the points on one side of the corridor centre line in a frame: that frame's
  /// innermost reach (0: the innermost point; rownav)
  double quantile = 0.0;
  int min_points = 10;  ///< [-] fewer points on a side in a frame: that frame saw no canopy there
  /// [-] frames kept (60 s at 10 Hz, some 40 m of row): shoots and crowns protrude in clumps a
  /// few metres apart, and the deepest clumps are what the robot meets (zoo:1:30: the median
  /// of 3 s of frames read 0.45 m from the centre, clumps ahead reached 0.22 m)
  int frames = 600;
  /// [-] of the kept frames' reaches: the reach is this low quantile of them, the depth the
  /// canopy reaches in clumps, not one frame's stray return (rownav)
  double frame_quantile = 0.05;
  /// [m] canopy ahead may reach this much further in than the canopy driven beside (rownav)
  double margin = 0.1;
  /// [-] of the robot's half width: canopy is never taken to reach deeper into the footprint
  /// than this, whatever was measured (a person standing this far into the robot's path stops
  /// it; rownav: 0.5 of a 0.6 m robot is 0.15 m, the shoots of a 1.6 m vineyard)
  double max_intrusion = 0.5;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("enabled", s.enabled);
    v("behind", s.behind);
    v("quantile", s.quantile);
    v("min_points", s.min_points);
    v("frames", s.frames);
    v("frame_quantile", s.frame_quantile);
    v("margin", s.margin);
    v("max_intrusion", s.max_intrusion);
  }
  void validate() const {
    core::check_non_negative(behind, "behind");
    core::check_range(quantile, 0.0, 1.0, "quantile");
    core::check_positive(min_points, "min_points");
    core::check_positive(frames, "frames");
    core::check_range(frame_quantile, 0.0, 1.0, "frame_quantile");
    core::check_non_negative(margin, "margin");
    core::check_range(max_intrusion, 0.0, 1.0, "max_intrusion");
  }
};

/// Which points of a sweep are the obstacle band's (height above the ground and base-frame z):
/// this frame's ObstacleBandConfig heights and the robot's top, set by the caller (NavStack), so
/// no default is restated here.
struct HeightBand {
  double min_height;  ///< [m] above the local ground
  double max_height;  ///< [m] above the local ground
  double top;         ///< [m] base-frame z: higher points pass over the robot
};

/// A low quantile over recent frames of the innermost reach of each side's canopy, in the corridor
/// frame.
class CanopyReachEstimator {
 public:
  explicit CanopyReachEstimator(const CanopyReachConfig& config = {});
  /// One 3D sweep (base frame), its ground and the tracked corridor centre line (base frame,
  /// forward): band points from `behind` to `base_to_front` are the canopy beside the robot.
  /// Never throws; non-finite points are skipped.
  void update(const core::PointCloud& cloud_base, const preprocess::GroundEstimator& ground,
              const HeightBand& band, const core::Line2& centre_base, double base_to_front);
  /// [m] innermost reach of the left (+1) or right (-1) canopy: distance from the centre line
  /// towards that side (+infinity: not measured).
  double reach(double side) const;
  /// Removes from `points` (base frame, obstacle candidates) those the canopy explains: on a
  /// side whose reach is measured, no further in than reach - margin from `centre_base`, and
  /// not deeper into the footprint (|y| < half_width) than max_intrusion * half_width.
  void drop_canopy(std::vector<Eigen::Vector2f>& points, const core::Line2& centre_base,
                   double half_width) const;
  /// Forgets the history (NavStack: a new mission; update() without a finite centre line).
  void reset();

 private:
  CanopyReachConfig config_;
  std::vector<float> side_[2];     // reused per frame: [0] right, [1] left
  std::deque<double> history_[2];  // per-frame reach, +inf: none
  double reach_[2] = {std::numeric_limits<double>::infinity(),
                      std::numeric_limits<double>::infinity()};  // frame_quantile of history_
};

}  // namespace rownav::navigate
