// The robot-file part of NavStackConfig (io/nav_stack_setup.hpp).
#include "rownav/io/nav_stack_setup.hpp"

#include <string>
#include <vector>

#include "rownav/io/localize_setup.hpp"
#include "rownav/io/yaml_config.hpp"

namespace rownav::io {

core::RobotSpec load_robot_spec(const std::filesystem::path& file) {
  const std::vector<std::string> ignore(kSimulatorRobotKeys.begin(), kSimulatorRobotKeys.end());
  core::RobotSpec spec;
  decode_config(load_yaml_file(file), spec, file.string(), ignore);
  return spec;
}

void nav_stack_robot_limits(navigate::NavStackConfig& nav, const core::RobotSpec& robot) {
  nav.robot.width = robot.width;
  nav.robot.length = robot.length;
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
}

void nav_stack_robot(navigate::NavStackConfig& nav, const core::RobotSpec& robot, int ticks_per_rev,
                     double lidar_rate_hz) {
  nav_stack_robot_limits(nav, robot);
  nav.localizer = localizer_config_for(robot, ticks_per_rev);
  nav.stack.sweep_period = 1.0 / lidar_rate_hz;
}

}  // namespace rownav::io
