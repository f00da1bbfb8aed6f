// The robot-file part of NavStackConfig (io/nav_stack_setup.hpp).
#include "rownav/io/nav_stack_setup.hpp"

#include "rownav/io/localize_setup.hpp"

namespace rownav::io {

void nav_stack_robot(navigate::NavStackConfig& nav, const sim::RobotConfig& robot,
                     const sim::SimConfig& sensors) {
  nav.robot.width = robot.width;
  nav.robot.base_to_front = robot.base_to_front;
  nav.robot.turn = {robot.can_turn_in_place(), robot.min_turn_radius()};
  // The robot's limits are applied to every command, as a base controller would (the
  // controllers and manoeuvres do not clamp themselves).
  nav.limits.max_speed = robot.max_speed;
  nav.limits.max_reverse_speed = robot.max_reverse_speed;
  nav.limits.max_yaw_rate = robot.max_yaw_rate;
  nav.limits.max_accel = robot.max_accel;
  nav.limits.max_yaw_accel = robot.max_yaw_accel;
  nav.limits.min_turn_radius = robot.min_turn_radius();
  nav.localizer = localizer_config_for(robot, sensors);
  nav.stack.sweep_period = 1.0 / sensors.lidar.rate_hz;
}

}  // namespace rownav::io
