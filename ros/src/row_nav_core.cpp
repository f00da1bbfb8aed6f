// rownav_node's adapter: ROS messages -> navigate::NavStack -> what to publish.
#include "rownav_ros/row_nav_core.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <utility>

#include "rownav/io/controller_registry.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/io/tracker_registry.hpp"

namespace rownav::ros_bridge {

namespace {

/// The NavStack configuration of the node: the same files as `rownav run`, the robot's own
/// odometry as the pose source.
navigate::NavStackConfig stack_config(const StackSetup& s) {
  navigate::NavStackConfig c;
  c.navigator = s.navigator;
  c.end_of_row = s.end_of_row;
  c.robot = s.robot;
  c.limits = s.limits;
  // The robot's odometry, or rownav's own wheel odometry + IMU EKF on its joint states (the
  // localizer `rownav run` measures, from the same robot file).
  const bool own = s.node.odometry == "joint_states";
  c.stack.odometry = own ? navigate::OdometryInput::wheels_imu : navigate::OdometryInput::external;
  c.localizer = s.localizer;
  c.stack.gyro_yaw_rate = s.node.use_imu;
  c.stack.odometry_history = s.node.odom_history;
  c.stack.max_extrapolation = s.node.max_extrapolation;
  c.stack.command_period = s.node.nominal_frame_period;
  return c;
}

}  // namespace

std::unique_ptr<navigate::NavStack> make_node_stack(const StackSetup& s,
                                                    const Eigen::Isometry3d& T_base_lidar) {
  const NodeConfig& n = s.node;
  navigate::NavStackParts parts;
  parts.pipeline = std::make_unique<detect::DetectionPipeline>(
      io::make_pipeline(n.detector, n.detect_config, T_base_lidar));
  parts.tracker = io::make_tracker(n.tracker, n.track_config);
  parts.controller = io::make_controller(n.controller, n.control_config);
  return std::make_unique<navigate::NavStack>(stack_config(s), std::move(parts), s.order,
                                              s.mission.first_turn);
}

RowNavCore::RowNavCore(StackSetup setup)
    : setup_(std::move(setup)),
      stack_(make_node_stack(setup_, Eigen::Isometry3d::Identity())),
      mission_(setup_.node.autostart),
      navsat_(setup_.node.gnss),
      joints_(setup_.node.wheels) {}

RowNavCore::~RowNavCore() = default;

void RowNavCore::set_mount(const Eigen::Isometry3d& T_base_lidar) {
  // Known once, before the first frame (parameter or tf): the stack starts with it.
  stack_ = make_node_stack(setup_, T_base_lidar);
  mount_set_ = true;
  started_ = false;
  last_odom_stamp_.reset();
}

MissionAnswer RowNavCore::start() {
  // A pause during which the robot was carried out of its rows or into another corridor: a
  // resume would steer into whatever corridor is tracked now (issue 15). The pause stays.
  if (!mission_.starts_new_mission(navigator().state()) && mission_.phase() == MissionPhase::paused)
    if (auto why = stack_->resume_blocker())
      return {false, "not resumed: " + *why +
                         "; put the robot at a corridor's entrance, then ~stop and ~start a new "
                         "mission (~mission, ~corridor_count)"};
  MissionAnswer a = mission_.start(navigator().state());
  if (a.new_mission) stack_->restart_mission();
  return a;
}

MissionAnswer RowNavCore::start(const NodeConfig& node) {
  if (!mission_.starts_new_mission(navigator().state())) return start();
  navigate::MissionPlan plan;
  std::vector<int> order;
  try {
    plan = load_node_mission(node);
    order = mission_order(node, plan);
  } catch (const std::exception& e) {
    return {false, std::string("no new mission: ") + e.what()};
  }
  MissionAnswer a = mission_.start(navigator().state());
  setup_.node.mission = node.mission;
  setup_.node.corridor_count = node.corridor_count;
  setup_.mission = plan;
  setup_.order = order;
  stack_->restart_mission(std::move(order), plan.first_turn);
  const std::string first = std::to_string(setup_.order.front());
  a.message += ", " + std::to_string(setup_.order.size()) + " corridors from corridor " + first;
  return a;
}

const std::vector<Eigen::Vector2f>& RowNavCore::last_points() const {
  return stack_->pipeline().last_points();
}

FrameResult RowNavCore::fail(double stamp, std::string why) {
  FrameResult r;
  r.stamp = stamp;
  r.error = std::move(why);
  r.state = stack_->navigator().state();
  r.stop_reason = stack_->navigator().stop_reason();
  return r;
}

FrameResult RowNavCore::on_cloud(const sensor_msgs::PointCloud2& msg) {
  const double stamp = to_sec(msg.header.stamp);
  try {
    if (!mount_set_) return fail(stamp, "no LiDAR mount (T_base_lidar) yet");
    stack_->on_cloud(to_point_cloud(msg));
    return frame(stamp);
  } catch (const std::exception& e) {
    return fail(stamp, e.what());
  }
}

FrameResult RowNavCore::on_scan(const sensor_msgs::LaserScan& msg) {
  const double stamp = to_sec(msg.header.stamp);
  try {
    if (!mount_set_) return fail(stamp, "no LiDAR mount (T_base_lidar) yet");
    stack_->on_scan(to_scan(msg));
    return frame(stamp);
  } catch (const std::exception& e) {
    return fail(stamp, e.what());
  }
}

void RowNavCore::on_imu(const sensor_msgs::Imu& msg) {
  try {
    stack_->on_imu(to_imu(msg));
  } catch (const std::exception&) {
    // a malformed message: nothing to keep
  }
}

NavSatConversion RowNavCore::on_fix(const sensor_msgs::NavSatFix& msg) {
  NavSatConversion c = navsat_.convert(msg);
  stack_->on_gnss(c.fix);
  return c;
}

std::optional<core::Twist2> RowNavCore::on_odom(const nav_msgs::Odometry& msg) {
  if (setup_.node.odometry != "odom") return std::nullopt;  // the joint states are the source
  try {
    const OdomSample s = to_odom(msg);
    if (!stack_->on_odometry({s.stamp, s.T_odom_base, s.twist}))
      return std::nullopt;  // late or not finite
    return pose_received(s.stamp);
  } catch (const std::exception&) {
    return core::Twist2{};  // a stop, to be safe
  }
}

JointAnswer RowNavCore::on_joints(const sensor_msgs::JointState& msg) {
  JointAnswer a;
  if (setup_.node.odometry != "joint_states") {
    a.skipped = "the pose source is nav_msgs/Odometry (~odometry: odom)";
    return a;
  }
  try {
    JointConversion c = joints_.convert(msg);
    if (!c.sample) {
      a.skipped = std::move(c.skipped);
      return a;
    }
    if (!stack_->on_encoders(*c.sample)) {
      a.skipped = "wheel sample not newer than the last one";
      return a;
    }
    a.cmd = pose_received(c.sample->stamp);
  } catch (const std::exception& e) {
    a.cmd = core::Twist2{};  // a stop, to be safe
    a.skipped = e.what();
  }
  return a;
}

std::optional<core::Twist2> RowNavCore::pose_received(double stamp) {
  last_odom_stamp_ = stamp;
  if (!started_) return std::nullopt;
  return mission_.gate(command_at(stamp).cmd);
}

std::optional<OdomSample> RowNavCore::own_odometry(double stamp) const {
  if (setup_.node.odometry != "joint_states" || !last_odom_stamp_) return std::nullopt;
  const auto T = stack_->T_odom_base(stamp);
  if (!T) return std::nullopt;
  return OdomSample{stamp, *T, stack_->twist(), setup_.node.odom_frame, setup_.node.base_frame};
}

TickResult RowNavCore::tick(double stamp) {
  TickResult r;
  if (!started_) {  // nothing processed yet: stand still
    r.state = stack_->navigator().state();
    r.health = navigate::InputHealth::lidar_stale;
    return r;
  }
  navigate::NavCommand c = command_at(stamp);
  r.cmd = mission_.gate(c.cmd);
  r.health = c.health;
  r.lidar_age = c.lidar_age;
  r.odometry_age = c.odometry_age;
  r.state = c.state;
  r.stop_reason = c.stop_reason;
  r.events = std::move(c.events);
  return r;
}

navigate::NavCommand RowNavCore::command_at(double stamp) {
  if (last_command_stamp_ && std::isfinite(stamp)) stamp = std::max(stamp, *last_command_stamp_);
  if (std::isfinite(stamp)) last_command_stamp_ = stamp;
  stack_->set_held(!mission_.running());  // the one place the stack is commanded
  return stack_->command(stamp);
}

FrameResult RowNavCore::frame(double stamp) {
  if (!last_odom_stamp_) {
    command_at(stamp);  // the frame is consumed (detected), the command stays zero
    return fail(stamp, "no odometry received yet");
  }
  // The stack works at the newest instant known (as the simulator loop does); the tracker gets
  // the pose at the start of the sweep (the frame stamp).
  navigate::NavCommand c = command_at(std::max(stamp, *last_odom_stamp_));
  if (!c.frame) return fail(stamp, "frame dropped: not newer than the last one");
  if (!c.frame->tracking)
    return fail(stamp, "no odometry at the frame stamp (frame " + std::to_string(stamp) +
                           " s, odometry up to " + std::to_string(*last_odom_stamp_) + " s)");
  started_ = true;
  FrameResult r;
  r.ok = true;
  r.held = stack_->held();
  r.stamp = stamp;
  r.cmd = c.cmd;
  r.tracking = std::move(*c.frame->tracking);
  r.state = c.state;
  r.stop_reason = c.stop_reason;
  r.events = std::move(c.events);
  r.corridor = c.corridor;
  return r;
}

}  // namespace rownav::ros_bridge
