#pragma once
/// @file ros_node.hpp rownav_node's ROS side: parameters, subscriptions, tf2, publications.
/// The processing is RowNavCore's.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/Twist.h>
#include <geometry_msgs/Vector3Stamped.h>
#include <ros/ros.h>
#include <std_msgs/Bool.h>
#include <std_msgs/String.h>
#include <std_srvs/Trigger.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <memory>
#include <string>

#include "rownav_ros/row_nav_core.hpp"

namespace rownav::ros_bridge {

/// The node. Topics (relative, remappable): subscribes `cloud` or `scan`, `odom` or
/// `joint_states` (~odometry; with joint states the node runs rownav's own wheel odometry +
/// IMU EKF and, with ~publish_tf, broadcasts odom -> base_link and publishes `~odom`), `imu`
/// (~use_imu), `fix` (sensor_msgs/NavSatFix), `~enable` (std_msgs/Bool); publishes `cmd_vel`
/// (unless observing only), `~tracking` (Vector3Stamped: lateral [m], heading [rad], spacing
/// [m]), `~state` (std_msgs/String), `~rows` (PoseArray of the tracked rows, base frame) and
/// `/diagnostics` (input ages, health, state; once a second). Services (std_srvs/Trigger):
/// `~start`, `~pause`, `~stop` (MissionControl). A timer re-evaluates cmd_vel at
/// ~watchdog_rate so that stale inputs stop the robot even when no message arrives; zero is
/// published on shutdown. docs/ros.md.
class RosNode {
 public:
  /// Reads the parameters and loads the stack; throws on a bad parameter or file.
  RosNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Publishes a zero command (the last one sent must not keep the robot moving).
  ~RosNode();

 private:
  void on_cloud(const sensor_msgs::PointCloud2::ConstPtr& msg);
  void on_scan(const sensor_msgs::LaserScan::ConstPtr& msg);
  void on_odom(const nav_msgs::Odometry::ConstPtr& msg);
  void on_joints(const sensor_msgs::JointState::ConstPtr& msg);
  /// ~odometry joint_states + ~publish_tf: the stack's pose at `stamp` as tf and on ~odom.
  void publish_own_odometry(double stamp);
  void on_imu(const sensor_msgs::Imu::ConstPtr& msg);
  void on_fix(const sensor_msgs::NavSatFix::ConstPtr& msg);
  void on_enable(const std_msgs::Bool::ConstPtr& msg);
  bool on_start(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool on_pause(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool on_stop(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  /// Fills the service's answer, logs it, sends zero at once unless running, publishes the state.
  bool answer(const MissionAnswer& a, std_srvs::Trigger::Response& res);
  /// Publishes ~state when the state to show for `nav` changed.
  void publish_state(navigate::NavState nav);
  void on_timer(const ros::TimerEvent& event);
  void publish_diagnostics(const TickResult& t);
  /// Looks T_base_lidar up once (base_frame <- frame); false while tf2 does not know it.
  bool ensure_mount(const std::string& frame, const ros::Time& stamp);
  void publish_frame(const FrameResult& r, const ros::Time& stamp);
  void publish_cmd(const core::Twist2& cmd);
  void publish_stop();

  ros::NodeHandle nh_, pnh_;
  std::unique_ptr<RowNavCore> core_;
  bool enabled_ = true;
  std::string last_state_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_broadcaster_;  // publish_tf only
  ros::Subscriber frame_sub_, odom_sub_, imu_sub_, fix_sub_, enable_sub_;
  ros::ServiceServer start_srv_, pause_srv_, stop_srv_;
  ros::Publisher cmd_pub_, tracking_pub_, state_pub_, rows_pub_, markers_pub_, diag_pub_, odom_pub_;
  ros::Timer watchdog_timer_;
  int ticks_ = 0;
};

}  // namespace rownav::ros_bridge
