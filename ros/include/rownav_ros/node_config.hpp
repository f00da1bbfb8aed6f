#pragma once
/// @file node_config.hpp The node's own settings (private ROS parameters, read generically
/// through `fields`), and the stack loaded from the same YAML files as the command line.
#include <string>
#include <vector>

#include "rownav/control/velocity_limits.hpp"
#include "rownav/core/config_fields.hpp"
#include "rownav/localize/localizer.hpp"
#include "rownav/navigate/end_of_row.hpp"
#include "rownav/navigate/mission_plan.hpp"
#include "rownav/navigate/navigator.hpp"
#include "rownav_ros/joint_state_conversion.hpp"
#include "rownav_ros/navsat_conversion.hpp"

namespace rownav::ros_bridge {

/// Private parameters of rownav_node (~name). Paths may be empty: that component's defaults.
/// The component names and files are those of `rownav run` (--detector, --detect-config, ...).
struct NodeConfig {
  std::string input = "cloud";  ///< "cloud" (PointCloud2 on `cloud`) or "scan" (`scan`)
  /// pose source: "odom" (the robot's nav_msgs/Odometry on `odom`) or "joint_states" (its wheel
  /// joints, sensor_msgs/JointState on `joint_states`, + the IMU on `imu` through rownav's own
  /// wheel odometry + EKF, the localizer `rownav run` measures; see `wheels`)
  std::string odometry = "odom";
  std::string detector = "hough_skew";   ///< io::detector_names()
  std::string detect_config;             ///< config/detect/<crop>.yaml
  std::string tracker = "model_filter";  ///< io::tracker_names()
  std::string track_config;              ///< config/track/default.yaml
  std::string controller = "stanley";    ///< io::controller_names()
  std::string control_config;            ///< config/control/default.yaml
  std::string mission;                   ///< config/missions/*.yaml (empty: MissionPlan{})
  std::string nav_config;                ///< navigate::NavigatorConfig YAML
  std::string end_of_row_config;         ///< navigate::EndOfRowConfig YAML
  std::string robot;                     ///< config/robots/*.yaml: velocity limits, footprint
  /// [corridors] in the block (given by the operator: there is no map); 0: the mission's
  /// highest corridor index + 1
  int corridor_count = 0;
  std::string base_frame = "base_link";  ///< REP 105 base frame
  /// T_base_lidar as [x, y, z, roll, pitch, yaw] (m, rad); empty: looked up in tf2 once
  std::vector<double> lidar_mount;
  bool enabled = true;  ///< publish cmd_vel (false: observe only)
  /// the mission runs from start-up (false: command zero, state `waiting`, until ~start)
  bool autostart = true;
  bool use_imu = false;               ///< gyro yaw rate replaces the odometry yaw rate
  double odom_history = 2.0;          ///< [s] odometry poses kept for frame-stamp interpolation
  double max_extrapolation = 0.2;     ///< [s] a frame may be this much newer than the odometry
  double nominal_frame_period = 0.1;  ///< [s] dt of the first command (acceleration limit)
  /// [Hz] the watchdog timer: cmd_vel is re-evaluated (zero on stale inputs) at this rate even
  /// when no message arrives; diagnostics are published once a second
  double watchdog_rate = 20.0;
  NavSatConfig gnss;        ///< `fix` (sensor_msgs/NavSatFix) -> local ENU (~gnss/<key>)
  WheelJointConfig wheels;  ///< odometry "joint_states": which joints are wheels (~wheels/<key>)
  /// odometry "joint_states": broadcast the stack's own pose as tf odom_frame -> base_frame and
  /// publish it on ~odom (REP 105; nobody else does then). Off when the robot's driver already
  /// broadcasts that transform.
  bool publish_tf = true;
  std::string odom_frame = "odom";  ///< REP 105 odometry frame of publish_tf

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("input", s.input);
    v("odometry", s.odometry);
    v("detector", s.detector);
    v("detect_config", s.detect_config);
    v("tracker", s.tracker);
    v("track_config", s.track_config);
    v("controller", s.controller);
    v("control_config", s.control_config);
    v("mission", s.mission);
    v("nav_config", s.nav_config);
    v("end_of_row_config", s.end_of_row_config);
    v("robot", s.robot);
    v("corridor_count", s.corridor_count);
    v("base_frame", s.base_frame);
    v("lidar_mount", s.lidar_mount);
    v("enabled", s.enabled);
    v("autostart", s.autostart);
    v("use_imu", s.use_imu);
    v("odom_history", s.odom_history);
    v("max_extrapolation", s.max_extrapolation);
    v("nominal_frame_period", s.nominal_frame_period);
    v("watchdog_rate", s.watchdog_rate);
    v("gnss", s.gnss);
    v("wheels", s.wheels);
    v("publish_tf", s.publish_tf);
    v("odom_frame", s.odom_frame);
  }
  void validate() const;
};

/// Everything the per-frame processing needs, loaded and validated.
struct StackSetup {
  NodeConfig node;
  navigate::MissionPlan mission;
  std::vector<int> order;  ///< resolved corridor order
  navigate::NavigatorConfig navigator;
  navigate::EndOfRowConfig end_of_row;
  navigate::RobotLimits robot;
  control::VelocityLimits limits;
  /// odometry "joint_states": the robot file's wheel odometry model at wheels.ticks_per_rev
  localize::LocalizerConfig localizer;
};

/// Loads the files named in `node` (mission, navigator, end of row, robot) with the CLI's strict
/// loaders and resolves the corridor order. Throws io::InputError / std::invalid_argument.
StackSetup load_stack(const NodeConfig& node);

/// The mission file named by `node` (MissionPlan{} when none). Throws io::InputError.
navigate::MissionPlan load_node_mission(const NodeConfig& node);

/// The corridor order of `plan` for `node` (its corridor_count, or the one the plan implies).
/// Throws std::invalid_argument naming the field.
std::vector<int> mission_order(const NodeConfig& node, const navigate::MissionPlan& plan);

}  // namespace rownav::ros_bridge
