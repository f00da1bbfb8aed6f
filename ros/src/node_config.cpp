// The node's settings and the stack's files.
#include "rownav_ros/node_config.hpp"

#include "rownav/io/nav_stack_setup.hpp"

#include <algorithm>

#include "rownav/io/localize_setup.hpp"
#include "rownav/io/mission_io.hpp"
#include "rownav/io/yaml_config.hpp"

namespace rownav::ros_bridge {

void NodeConfig::validate() const {
  core::check(input == "cloud" || input == "scan", "input",
              "must be cloud or scan (got '" + input + "')");
  core::check(odometry == "odom" || odometry == "joint_states", "odometry",
              "must be odom or joint_states (got '" + odometry + "')");
  core::check(!odom_frame.empty(), "odom_frame", "must not be empty");
  core::check_non_negative(corridor_count, "corridor_count");
  core::check(!base_frame.empty(), "base_frame", "must not be empty");
  core::check(lidar_mount.empty() || lidar_mount.size() == 6, "lidar_mount",
              "must be empty or [x, y, z, roll, pitch, yaw]");
  core::check_positive(odom_history, "odom_history");
  core::check_non_negative(max_extrapolation, "max_extrapolation");
  core::check_positive(nominal_frame_period, "nominal_frame_period");
  core::check_range(watchdog_rate, 1.0, 1000.0, "watchdog_rate");
  core::validate_nested(gnss, "gnss");
  core::validate_nested(wheels, "wheels");
}

namespace {

template <class T>
T load_or_default(const std::string& path) {
  return path.empty() ? T{} : io::load_config<T>(path);
}

/// The corridor count the order is resolved against: given, or implied by the mission.
int corridor_count_for(const NodeConfig& node, const navigate::MissionPlan& plan) {
  if (node.corridor_count > 0) return node.corridor_count;
  int highest = plan.start_corridor;
  for (int c : plan.corridors) highest = std::max(highest, c);
  return highest + 1;
}

}  // namespace

navigate::MissionPlan load_node_mission(const NodeConfig& node) {
  return node.mission.empty() ? navigate::MissionPlan{} : io::load_mission(node.mission);
}

std::vector<int> mission_order(const NodeConfig& node, const navigate::MissionPlan& plan) {
  return navigate::resolve_order(plan, corridor_count_for(node, plan));
}

StackSetup load_stack(const NodeConfig& node) {
  node.validate();
  StackSetup s;
  s.node = node;
  s.mission = load_node_mission(node);
  s.order = mission_order(node, s.mission);
  s.navigator = load_or_default<navigate::NavigatorConfig>(node.nav_config);
  s.end_of_row = load_or_default<navigate::EndOfRowConfig>(node.end_of_row_config);
  // Footprint and limits exactly as `rownav run` derives them from the same robot file.
  navigate::NavStackConfig stack;
  // The robot file as the stack knows it (core::RobotSpec): the node links no simulator.
  const core::RobotSpec spec =
      node.robot.empty() ? core::RobotSpec{} : io::load_robot_spec(node.robot);
  io::nav_stack_robot_limits(stack, spec);
  s.localizer = io::localizer_config_for(spec, node.wheels.ticks_per_rev);
  s.robot = stack.robot;
  s.limits = stack.limits;
  s.limits.validate();
  return s;
}

}  // namespace rownav::ros_bridge
