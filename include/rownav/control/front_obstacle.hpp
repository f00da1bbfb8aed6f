#pragma once
/// @file front_obstacle.hpp Distance to the nearest obstacle in a rectangle in front of the robot,
/// and the forward speed reduced by it (Bertoglio 2023, 003_25dc0df51a1e5faf.txt sec. II-B: "a
/// rectangle in front of the robot to calculate the target speed based on the distance between
/// the robot and any obstacles").
#include <Eigen/Core>
#include <span>

#include "rownav/core/config_fields.hpp"

namespace rownav::control {

/// The front rectangle, base frame: x in [front_x, front_x + max_distance], |y| <= half width.
struct FrontRectConfig {
  double robot_width = 0.8;   ///< [m] width of the robot body
  double margin = 0.1;        ///< [m] added on each side of the body
  double front_x = 0.5;       ///< [m] x of the robot front in the base frame
  double max_distance = 3.0;  ///< [m] length of the rectangle ahead of the front
  int min_points = 1;         ///< [points] an obstacle is at least this many points (noise guard)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("robot_width", s.robot_width);
    v("margin", s.margin);
    v("front_x", s.front_x);
    v("max_distance", s.max_distance);
    v("min_points", s.min_points);
  }
  void validate() const;
};

/// Distance [m] along x from the robot front to the `min_points`-th nearest point inside the
/// front rectangle; +infinity when the rectangle holds fewer points. Non-finite points are
/// ignored. Feeds ControlInput::obstacle_distance. Never throws.
double front_obstacle_distance(std::span<const Eigen::Vector2f> points_base,
                               const FrontRectConfig& config);

/// Linear speed reduction with the obstacle distance (Bertoglio 2023 sec. II-B; the paper gives
/// no distances, these are rownav's).
struct SlowdownConfig {
  double slow_down_distance = 2.0;  ///< [m] full speed beyond this obstacle distance
  double stop_distance = 0.5;       ///< [m] zero speed at or below this distance

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("slow_down_distance", s.slow_down_distance);
    v("stop_distance", s.stop_distance);
  }
  void validate() const;
};

/// `speed_ref` scaled linearly from 1 at slow_down_distance to 0 at stop_distance; NaN distance
/// counts as an obstacle at 0 (stop), +infinity as clear. Never throws.
double obstacle_limited_speed(double speed_ref, double obstacle_distance,
                              const SlowdownConfig& config);

}  // namespace rownav::control
