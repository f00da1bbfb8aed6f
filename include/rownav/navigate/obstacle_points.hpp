#pragma once
/// @file obstacle_points.hpp The points that can be obstacles: of a 3D sweep, those ahead of the
/// robot whose height above the local ground lies in a band. Low weeds and grass between crop
/// rows are not obstacles (issue 10: in maize the weeds in the 2D detection band stopped the
/// robot); a person, a box or a post is. 2D scans have no heights: their points are used as they
/// are (a scanner mounted low sees what it would hit).
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/navigate/canopy_reach.hpp"
#include "rownav/navigate/ground_cover.hpp"
#include "rownav/preprocess/ground.hpp"

namespace rownav::navigate {

/// Which 3D points count for the obstacle stop and the controllers' slow-down.
struct ObstacleBandConfig {
  /// [m] above the local ground; lower points are ground cover (weeds 'some' in rownav's fields
  /// reach 0.25 m; a person's legs, a box, a post are all taller)
  double min_height = 0.3;
  double max_height = 2.5;  ///< [m] higher points pass over the robot (branches, wires)
  /// [m] top of the robot in the base frame (body, mast, sensors; the base origin on the
  /// ground): points higher in the base frame pass over it (tree crowns over the corridor,
  /// branches, wires; issue 10: orchard crowns 0.85-1 m above the ground stopped a robot whose
  /// LiDAR sits at 0.75 m). Base-frame z, not height above the estimated ground: the robot is
  /// rigid, and the ground estimate under a crown can be off by 0.3 m. 0: the LiDAR mount height
  /// plus sensor_top.
  double robot_top = 0.0;
  double sensor_top = 0.1;  ///< [m] LiDAR housing and margin above its mount point (robot_top 0)
  /// The band's lower end follows the ground cover the robot drives through (ground_cover.hpp)
  GroundCoverConfig cover;
  /// In a row, the followed rows' canopy at the robot's flanks is no obstacle (canopy_reach.hpp)
  CanopyReachConfig canopy;
  double range = 6.0;       ///< [m] ahead of the base origin (covers the slow-down rectangle)
  double half_width = 1.0;  ///< [m] either side of the robot's centre line

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("min_height", s.min_height);
    v("max_height", s.max_height);
    v("robot_top", s.robot_top);
    v("sensor_top", s.sensor_top);
    v("cover", s.cover);
    v("canopy", s.canopy);
    v("range", s.range);
    v("half_width", s.half_width);
  }
  void validate() const {
    core::check_non_negative(min_height, "min_height");
    core::check(max_height > min_height, "max_height", "must be > min_height");
    core::check_positive(range, "range");
    core::check_positive(half_width, "half_width");
    core::check_non_negative(robot_top, "robot_top");
    core::check_non_negative(sensor_top, "sensor_top");
    core::validate_nested(cover, "cover");
    core::validate_nested(canopy, "canopy");
  }
};

/// (x, y) of the points of `cloud_base` (base frame) in front of the robot (0 < x < range,
/// |y| < half_width) whose height above `ground` is within the band and whose base-frame z is
/// at most `top` (the robot's top: robot_top, or what NavStack derives); non-finite points are
/// skipped. Never throws.
std::vector<Eigen::Vector2f> obstacle_points(const core::PointCloud& cloud_base,
                                             const preprocess::GroundEstimator& ground,
                                             const ObstacleBandConfig& band,
                                             double top = std::numeric_limits<double>::infinity());

}  // namespace rownav::navigate
