// Per-frame processing of rownav_node (mirrors io::run_closed_loop with ROS data).
#include "rownav_ros/row_nav_core.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <utility>

#include "rownav/control/velocity_limits.hpp"
#include "rownav/io/controller_registry.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/io/tracker_registry.hpp"

namespace rownav::ros_bridge {

namespace {

/// A gyro sample older than this is not used for the twist.
constexpr double kImuMaxAge = 0.5;  // [s]
/// Smallest time step of the acceleration limit between two commands.
constexpr double kMinDt = 1e-3;  // [s]

bool terminal(navigate::NavState s) {
  return s == navigate::NavState::done || s == navigate::NavState::safe_stop;
}

}  // namespace

RowNavCore::RowNavCore(StackSetup setup)
    : setup_(std::move(setup)),
      odom_(setup_.node.odom_history, setup_.node.max_extrapolation) {
  const NodeConfig& n = setup_.node;
  pipeline_ = std::make_unique<detect::DetectionPipeline>(
      io::make_pipeline(n.detector, n.detect_config));
  tracker_ = io::make_tracker(n.tracker, n.track_config);
  controller_ = io::make_controller(n.controller, n.control_config);
  end_of_row_ = std::make_unique<navigate::EndOfRowDetector>(setup_.end_of_row);
  navigator_ = std::make_unique<navigate::Navigator>(setup_.navigator, setup_.order,
                                                     setup_.mission.first_turn, *tracker_,
                                                     *controller_, *end_of_row_);
}

RowNavCore::~RowNavCore() = default;

void RowNavCore::set_mount(const Eigen::Isometry3d& T_base_lidar) {
  const NodeConfig& n = setup_.node;
  pipeline_ = std::make_unique<detect::DetectionPipeline>(
      io::make_pipeline(n.detector, n.detect_config, T_base_lidar));
  mount_set_ = true;
}

const std::vector<Eigen::Vector2f>& RowNavCore::last_points() const {
  return pipeline_->last_points();
}

FrameResult RowNavCore::fail(double stamp, std::string why) {
  FrameResult r;
  r.stamp = stamp;
  r.error = std::move(why);
  r.state = navigator_->state();
  r.stop_reason = navigator_->stop_reason();
  last_cmd_ = {};  // a stop: the next command accelerates from zero
  last_cmd_stamp_ = stamp;
  return r;
}

FrameResult RowNavCore::on_cloud(const sensor_msgs::PointCloud2& msg) {
  const double stamp = to_sec(msg.header.stamp);
  try {
    if (!mount_set_) return fail(stamp, "no LiDAR mount (T_base_lidar) yet");
    return step(pipeline_->process(to_point_cloud(msg)));
  } catch (const std::exception& e) {
    return fail(stamp, e.what());
  }
}

FrameResult RowNavCore::on_scan(const sensor_msgs::LaserScan& msg) {
  const double stamp = to_sec(msg.header.stamp);
  try {
    if (!mount_set_) return fail(stamp, "no LiDAR mount (T_base_lidar) yet");
    return step(pipeline_->process(to_scan(msg)));
  } catch (const std::exception& e) {
    return fail(stamp, e.what());
  }
}

void RowNavCore::on_imu(const sensor_msgs::Imu& msg) {
  const core::ImuSample s = to_imu(msg);
  if (std::isfinite(s.stamp) && std::isfinite(s.angular_velocity.z())) imu_ = s;
}

core::Twist2 RowNavCore::limit(const core::Twist2& cmd, double stamp) {
  // Two commands at the same instant may not differ by more than kMinDt of acceleration.
  const double dt = last_cmd_stamp_ ? std::max(stamp - *last_cmd_stamp_, kMinDt)
                                    : setup_.node.nominal_frame_period;
  last_cmd_ = control::apply_limits(cmd, last_cmd_, dt, setup_.limits);
  last_cmd_stamp_ = last_cmd_stamp_ ? std::max(*last_cmd_stamp_, stamp) : stamp;
  return last_cmd_;
}

std::optional<core::Twist2> RowNavCore::on_odom(const nav_msgs::Odometry& msg) {
  try {
    const OdomSample s = to_odom(msg);
    if (!odom_.push({s.stamp, s.T_odom_base, s.twist})) return std::nullopt;
    if (!started_) return std::nullopt;
    if (terminal(navigator_->state())) return limit({}, s.stamp);
    return limit(navigator_->hold(s.stamp, s.T_odom_base).cmd, s.stamp);
  } catch (const std::exception&) {
    return core::Twist2{};  // hold() and apply_limits() do not throw; a stop, to be safe
  }
}

FrameResult RowNavCore::step(const core::RowObservation& obs) {
  const auto latest = odom_.latest();
  if (!latest) return fail(obs.stamp, "no odometry received yet");
  const auto T_frame = odom_.at(obs.stamp);
  if (!T_frame)
    return fail(obs.stamp, "no odometry at the frame stamp (frame " + std::to_string(obs.stamp) +
                               " s, odometry up to " + std::to_string(latest->stamp) + " s)");
  navigate::NavInput in;
  // The navigator works at the newest instant known (as the simulator loop does); the tracker
  // gets the pose at the start of the sweep (the frame stamp).
  in.stamp = std::max(obs.stamp, latest->stamp);
  in.T_odom_base = obs.stamp > latest->stamp ? *T_frame : latest->T_odom_base;
  in.twist = latest->twist;
  if (setup_.node.use_imu && imu_ && std::abs(imu_->stamp - in.stamp) < kImuMaxAge)
    in.twist.omega = imu_->angular_velocity.z();
  in.observation = obs;
  in.tracking = tracker_->update(obs, *T_frame);
  in.end_of_row =
      end_of_row_->update(pipeline_->last_cloud_base(), pipeline_->last_points(), in.tracking);
  in.points_base = pipeline_->last_points();
  in.robot = setup_.robot;
  navigate::NavOutput out = navigator_->step(in);
  started_ = true;
  FrameResult r;
  r.ok = true;
  r.stamp = obs.stamp;
  r.cmd = limit(terminal(out.state) ? core::Twist2{} : out.cmd, in.stamp);
  r.tracking = std::move(in.tracking);
  r.state = out.state;
  r.stop_reason = out.stop_reason;
  r.events = std::move(out.events);
  r.corridor = out.corridor;
  return r;
}

}  // namespace rownav::ros_bridge
