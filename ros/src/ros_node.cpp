// rownav_node's ROS side.
#include "rownav_ros/ros_node.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

#include "rownav/core/config_fields.hpp"
#include "rownav_ros/ros_params.hpp"
#include "rownav_ros/row_markers.hpp"

namespace rownav::ros_bridge {

namespace {

/// NodeConfig from ~params; the navigator / end-of-row files may be overridden key by key
/// under ~navigator/... and ~end_of_row/... (the same names as in the YAML files).
StackSetup read_setup(const ros::NodeHandle& pnh) {
  NodeConfig node;
  read_config(pnh, "", node);
  StackSetup s = load_stack(node);
  read_config(pnh, "navigator", s.navigator);
  read_config(pnh, "end_of_row", s.end_of_row);
  return s;
}

Eigen::Isometry3d mount_from(const std::vector<double>& m) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(m[5], Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(m[4], Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(m[3], Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(m[0], m[1], m[2]);
  return T;
}

}  // namespace

RosNode::RosNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : nh_(nh), pnh_(pnh), tf_listener_(tf_buffer_) {
  core_ = std::make_unique<RowNavCore>(read_setup(pnh_));
  const NodeConfig& c = core_->setup().node;
  enabled_ = c.enabled;
  if (!c.lidar_mount.empty()) core_->set_mount(mount_from(c.lidar_mount));
  cmd_pub_ = nh_.advertise<geometry_msgs::Twist>("cmd_vel", 1);
  tracking_pub_ = pnh_.advertise<geometry_msgs::Vector3Stamped>("tracking", 10);
  state_pub_ = pnh_.advertise<std_msgs::String>("state", 1, /*latch=*/true);
  rows_pub_ = pnh_.advertise<geometry_msgs::PoseArray>("rows", 10);
  markers_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 2);
  if (c.input == "cloud")
    frame_sub_ = nh_.subscribe("cloud", 2, &RosNode::on_cloud, this);
  else
    frame_sub_ = nh_.subscribe("scan", 2, &RosNode::on_scan, this);
  if (c.odometry == "joint_states") {
    odom_sub_ = nh_.subscribe("joint_states", 100, &RosNode::on_joints, this);
    if (c.publish_tf) {
      tf_broadcaster_ = std::make_unique<tf2_ros::TransformBroadcaster>();
      odom_pub_ = pnh_.advertise<nav_msgs::Odometry>("odom", 50);
    }
  } else {
    odom_sub_ = nh_.subscribe("odom", 50, &RosNode::on_odom, this);
  }
  // Always: the IMU levels each sweep by gravity; its yaw rate is used only with ~use_imu.
  imu_sub_ = nh_.subscribe("imu", 200, &RosNode::on_imu, this);
  fix_sub_ = nh_.subscribe("fix", 10, &RosNode::on_fix, this);
  enable_sub_ = pnh_.subscribe("enable", 1, &RosNode::on_enable, this);
  start_srv_ = pnh_.advertiseService("start", &RosNode::on_start, this);
  pause_srv_ = pnh_.advertiseService("pause", &RosNode::on_pause, this);
  stop_srv_ = pnh_.advertiseService("stop", &RosNode::on_stop, this);
  diag_pub_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 1);
  watchdog_timer_ = nh_.createTimer(ros::Duration(1.0 / c.watchdog_rate), &RosNode::on_timer, this);
  // The state from the start (latched), not only after a first frame.
  std_msgs::String initial;
  initial.data = last_state_ = core_->state_name(core_->navigator().state());
  state_pub_.publish(initial);
  ROS_INFO(
      "rownav_node: %s input, pose from %s, detector %s, tracker %s, controller %s, %zu corridors, "
      "%s, %s",
      c.input.c_str(), c.odometry == "odom" ? "odom" : "joint_states + imu (own EKF)",
      c.detector.c_str(), c.tracker.c_str(), c.controller.c_str(), core_->setup().order.size(),
      enabled_ ? "driving" : "observing only",
      c.autostart ? "mission running" : "waiting for ~start");
}

RosNode::~RosNode() {
  if (ros::ok()) publish_stop();
}

void RosNode::on_timer(const ros::TimerEvent&) {
  const TickResult t = core_->tick(ros::Time::now().toSec());
  publish_cmd(t.cmd);
  for (const auto& e : t.events) ROS_WARN("rownav_node: %s", e.text.c_str());
  publish_state(t.state);
  if (ticks_++ % static_cast<int>(std::max(1.0, core_->setup().node.watchdog_rate)) == 0)
    publish_diagnostics(t);
}

void RosNode::publish_diagnostics(const TickResult& t) {
  diagnostic_msgs::DiagnosticArray a;
  a.header.stamp = ros::Time::now();
  diagnostic_msgs::DiagnosticStatus s;
  s.name = "rownav_node: inputs and mission";
  s.hardware_id = core_->setup().node.base_frame;
  const bool stopped = t.state == navigate::NavState::safe_stop;
  // Held (not running): the stack still tracks every frame, so a stale input is a real one.
  const bool held = !core_->mission().running();
  const std::string phase(core::enum_name(core_->mission().phase()));
  s.level = stopped                                 ? diagnostic_msgs::DiagnosticStatus::ERROR
            : t.health != navigate::InputHealth::ok ? diagnostic_msgs::DiagnosticStatus::WARN
                                                    : diagnostic_msgs::DiagnosticStatus::OK;
  s.message = stopped ? "safe stop: " + std::string(core::enum_name(t.stop_reason))
              : t.health == navigate::InputHealth::lidar_stale    ? "LiDAR stale: command zero"
              : t.health == navigate::InputHealth::odometry_stale ? "odometry stale: command zero"
              : held ? "mission " + phase + ": command zero"
                     : "ok";
  auto kv = [&](const std::string& k, const std::string& v) {
    diagnostic_msgs::KeyValue p;
    p.key = k, p.value = v;
    s.values.push_back(p);
  };
  kv("lidar_age_s", std::to_string(t.lidar_age));
  kv("odometry_age_s", std::to_string(t.odometry_age));
  kv("state", std::string(core::enum_name(t.state)));
  kv("mission", phase);
  const auto& st = core_->stack().stats();
  kv("frames", std::to_string(st.frames));
  kv("dropped_frames", std::to_string(st.dropped_frames));
  kv("dropped_odometry", std::to_string(st.dropped_odometry));
  kv("gnss_fixes", std::to_string(st.gnss));
  kv("gnss_fused", std::to_string(core_->stack().localizer().stats().gnss_used));
  a.status.push_back(s);
  diag_pub_.publish(a);
}

bool RosNode::ensure_mount(const std::string& frame, const ros::Time& stamp) {
  if (core_->has_mount()) return true;
  const std::string& base = core_->setup().node.base_frame;
  try {
    const auto t = tf_buffer_.lookupTransform(base, frame, stamp, ros::Duration(0.05));
    core_->set_mount(to_isometry(t.transform));
    ROS_INFO("rownav_node: T_%s_%s from tf2", base.c_str(), frame.c_str());
    return true;
  } catch (const std::exception& e) {
    ROS_WARN_THROTTLE(1.0, "rownav_node: no transform %s <- %s yet: %s", base.c_str(),
                      frame.c_str(), e.what());
    return false;
  }
}

void RosNode::on_cloud(const sensor_msgs::PointCloud2::ConstPtr& msg) {
  try {
    if (!ensure_mount(msg->header.frame_id, msg->header.stamp)) return publish_stop();
    publish_frame(core_->on_cloud(*msg), msg->header.stamp);
  } catch (const std::exception& e) {
    ROS_WARN_THROTTLE(1.0, "rownav_node: frame dropped: %s", e.what());
    publish_stop();
  }
}

void RosNode::on_scan(const sensor_msgs::LaserScan::ConstPtr& msg) {
  try {
    if (!ensure_mount(msg->header.frame_id, msg->header.stamp)) return publish_stop();
    publish_frame(core_->on_scan(*msg), msg->header.stamp);
  } catch (const std::exception& e) {
    ROS_WARN_THROTTLE(1.0, "rownav_node: frame dropped: %s", e.what());
    publish_stop();
  }
}

void RosNode::on_odom(const nav_msgs::Odometry::ConstPtr& msg) {
  try {
    if (const auto cmd = core_->on_odom(*msg)) publish_cmd(*cmd);
  } catch (const std::exception& e) {
    ROS_WARN_THROTTLE(1.0, "rownav_node: odometry dropped: %s", e.what());
    publish_stop();
  }
}

void RosNode::on_joints(const sensor_msgs::JointState::ConstPtr& msg) {
  const JointAnswer a = core_->on_joints(*msg);
  if (a.cmd) publish_cmd(*a.cmd);
  // Another joint group on the same topic is normal; anything else is worth a warning.
  if (!a.skipped.empty() && a.skipped != "no wheel joint in the message")
    ROS_WARN_THROTTLE(1.0, "rownav_node: joint states skipped: %s", a.skipped.c_str());
  if (a.skipped.empty()) publish_own_odometry(to_sec(msg->header.stamp));
}

void RosNode::publish_own_odometry(double stamp) {
  if (!tf_broadcaster_) return;
  const auto o = core_->own_odometry(stamp);
  if (!o) return;
  Eigen::Isometry3d T = o->T_odom_base.to_isometry();
  tf_broadcaster_->sendTransform(to_transform_msg(stamp, o->frame_id, o->child_frame_id, T));
  odom_pub_.publish(to_odom_msg(*o));
}

void RosNode::on_imu(const sensor_msgs::Imu::ConstPtr& msg) {
  try {
    core_->on_imu(*msg);
  } catch (const std::exception& e) {
    ROS_WARN_THROTTLE(1.0, "rownav_node: IMU sample dropped: %s", e.what());
  }
}

void RosNode::on_fix(const sensor_msgs::NavSatFix::ConstPtr& msg) {
  try {
    const NavSatConversion c = core_->on_fix(*msg);
    if (!c.rejected.empty())
      ROS_WARN_THROTTLE(1.0, "rownav_node: GNSS fix rejected: %s", c.rejected.c_str());
  } catch (const std::exception& e) {
    ROS_WARN_THROTTLE(1.0, "rownav_node: GNSS fix dropped: %s", e.what());
  }
}

bool RosNode::on_start(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  // A new mission reads ~mission and ~corridor_count as they are now (issue 15: another plan
  // without restarting the node); a resume does not.
  NodeConfig node = core_->setup().node;
  pnh_.getParam("mission", node.mission);
  pnh_.getParam("corridor_count", node.corridor_count);
  return answer(core_->start(node), res);
}

bool RosNode::on_pause(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  return answer(core_->pause(), res);
}

bool RosNode::on_stop(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  return answer(core_->stop(), res);
}

bool RosNode::answer(const MissionAnswer& a, std_srvs::Trigger::Response& res) {
  if (!core_->mission().running()) publish_stop();  // zero at once, not at the next message
  res.success = a.success;
  res.message = a.message;
  ROS_INFO("rownav_node: %s", a.message.c_str());
  publish_state(core_->navigator().state());
  return true;  // the call was handled; success says whether the request was granted
}

void RosNode::publish_state(navigate::NavState nav) {
  const std::string state = core_->state_name(nav);
  if (state == last_state_) return;
  std_msgs::String s;
  s.data = last_state_ = state;
  state_pub_.publish(s);
}

void RosNode::on_enable(const std_msgs::Bool::ConstPtr& msg) {
  if (msg->data == enabled_) return;
  if (!msg->data) publish_stop();  // the last command sent must not keep the robot moving
  enabled_ = msg->data;
  ROS_INFO("rownav_node: %s", enabled_ ? "driving" : "observing only");
}

void RosNode::publish_cmd(const core::Twist2& cmd) {
  if (enabled_) cmd_pub_.publish(to_twist_msg(cmd));
}

void RosNode::publish_stop() {
  publish_cmd({});
}

void RosNode::publish_frame(const FrameResult& r, const ros::Time& stamp) {
  if (!r.ok && !r.held) ROS_WARN_THROTTLE(1.0, "rownav_node: stopping: %s", r.error.c_str());
  publish_cmd(r.cmd);
  for (const auto& e : r.events) {
    if (e.kind == navigate::NavEventKind::moved_while_held)
      ROS_WARN("rownav_node: %s", e.text.c_str());  // an operator is to look before resuming
    else
      ROS_INFO("rownav_node: %s", e.text.c_str());
  }
  publish_state(r.state);
  if (!r.ok) return;
  geometry_msgs::Vector3Stamped t;
  t.header.stamp = stamp;
  t.header.frame_id = core_->setup().node.base_frame;
  t.vector.x = r.tracking.lateral_error;
  t.vector.y = r.tracking.heading_error;
  t.vector.z = r.tracking.row_spacing;
  tracking_pub_.publish(t);
  geometry_msgs::PoseArray rows;
  rows.header = t.header;
  for (const auto& row : r.tracking.rows) {
    geometry_msgs::Pose p;
    p.position.y = row.offset;
    p.orientation = yaw_quaternion(row.heading);
    rows.poses.push_back(p);
  }
  rows_pub_.publish(rows);
  if (markers_pub_.getNumSubscribers() > 0)
    markers_pub_.publish(row_markers(r.tracking, t.header.frame_id, stamp));
}

}  // namespace rownav::ros_bridge
