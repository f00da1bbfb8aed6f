#include "rownav/core/robot_spec.hpp"

#include <cmath>

#include "rownav/core/angle.hpp"

namespace rownav::core {

void RobotSpec::validate() const {
  check(!name.empty(), "name", "must not be empty");
  check_positive(track_width, "track_width");
  check_positive(wheelbase, "wheelbase");
  check_positive(wheel_radius, "wheel_radius");
  check_positive(max_speed, "max_speed");
  check_non_negative(max_reverse_speed, "max_reverse_speed");
  check_positive(max_yaw_rate, "max_yaw_rate");
  check_positive(max_accel, "max_accel");
  check_positive(max_yaw_accel, "max_yaw_accel");
  check_range(max_steer_deg, 1.0, 80.0, "max_steer_deg");
  check_positive(max_steer_rate_deg, "max_steer_rate_deg");
  check_positive(length, "length");
  check_positive(width, "width");
  check_range(base_to_front, 0.0, length, "base_to_front");
  check_non_negative(odometry_x_icr, "odometry_x_icr");
  check_range(odometry_alpha, 0.1, 1.5, "odometry_alpha");
}

double RobotSpec::min_turn_radius() const {
  if (drive != DriveKind::ackermann) return 0.0;
  return wheelbase / std::tan(deg2rad(max_steer_deg));
}

}  // namespace rownav::core
