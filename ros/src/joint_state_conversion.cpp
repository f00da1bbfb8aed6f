// sensor_msgs/JointState -> cumulative wheel counts for NavStack's own odometry.
#include "rownav_ros/joint_state_conversion.hpp"

#include <cmath>
#include <numbers>

#include "rownav_ros/conversions.hpp"

namespace rownav::ros_bridge {

void WheelJointConfig::validate() const {
  core::check(!left_joints.empty(), "left_joints", "must name at least one joint");
  core::check(!right_joints.empty(), "right_joints", "must name at least one joint");
  for (const auto& j : left_joints) core::check(!j.empty(), "left_joints", "empty joint name");
  for (const auto& j : right_joints) core::check(!j.empty(), "right_joints", "empty joint name");
  core::check_positive(ticks_per_rev, "ticks_per_rev");
  core::check_positive(max_velocity_gap, "max_velocity_gap");
}

JointStateConverter::JointStateConverter(const WheelJointConfig& config) : config_(config) {
  config_.validate();
}

namespace {

/// Index of `name` in the message, or -1.
int index_of(const sensor_msgs::JointState& msg, const std::string& name) {
  for (std::size_t i = 0; i < msg.name.size(); ++i)
    if (msg.name[i] == name) return static_cast<int>(i);
  return -1;
}

std::int64_t to_ticks(double angle, int ticks_per_rev) {
  return std::llround(angle / (2.0 * std::numbers::pi) * ticks_per_rev);
}

}  // namespace

std::optional<double> JointStateConverter::mean_of(const sensor_msgs::JointState& msg,
                                                   const std::vector<std::string>& joints,
                                                   bool positions, std::string& why) const {
  const auto& values = positions ? msg.position : msg.velocity;
  double sum = 0.0;
  for (const auto& j : joints) {
    const int i = index_of(msg, j);
    if (i < 0) {
      why = "joint '" + j + "' missing from the message";
      return std::nullopt;
    }
    if (static_cast<std::size_t>(i) >= values.size() || !std::isfinite(values[i])) {
      why = "joint '" + j + "' has no finite " + (positions ? "position" : "velocity");
      return std::nullopt;
    }
    sum += values[i];
  }
  return sum / static_cast<double>(joints.size());
}

sensor_msgs::JointState to_joint_state_msg(const core::WheelEncoderSample& s, int ticks_per_rev,
                                           const WheelJointConfig& joints) {
  sensor_msgs::JointState j;
  j.header.stamp.fromSec(s.stamp);
  const double rad_per_tick = 2.0 * std::numbers::pi / ticks_per_rev;
  j.name = {joints.left_joints.front(), joints.right_joints.front()};
  j.position = {rad_per_tick * static_cast<double>(s.left_ticks),
                rad_per_tick * static_cast<double>(s.right_ticks)};
  if (!joints.steering_joint.empty()) {
    j.name.push_back(joints.steering_joint);
    j.position.push_back(s.steering_angle);
  }
  return j;
}

JointConversion JointStateConverter::convert(const sensor_msgs::JointState& msg) {
  JointConversion out;
  const bool any = index_of(msg, config_.left_joints.front()) >= 0 ||
                   index_of(msg, config_.right_joints.front()) >= 0;
  if (!any) {
    out.skipped = "no wheel joint in the message";
    return out;
  }
  const double stamp = to_sec(msg.header.stamp);
  const bool positions = msg.position.size() == msg.name.size() && !msg.name.empty();
  if (!positions && msg.velocity.size() != msg.name.size()) {
    out.skipped = "neither a position nor a velocity per joint";
    return out;
  }
  const auto left = mean_of(msg, config_.left_joints, positions, out.skipped);
  const auto right =
      left ? mean_of(msg, config_.right_joints, positions, out.skipped) : std::nullopt;
  if (!left || !right) return out;
  core::WheelEncoderSample s;
  s.stamp = stamp;
  if (!config_.steering_joint.empty()) {
    const int i = index_of(msg, config_.steering_joint);
    if (i < 0 || !positions || !std::isfinite(msg.position[i])) {
      out.skipped = "steering joint '" + config_.steering_joint + "' has no finite position";
      return out;
    }
    s.steering_angle = msg.position[i];
  }
  if (positions) {
    left_angle_ = *left;
    right_angle_ = *right;
    last_velocity_stamp_.reset();
  } else {
    // Velocity-only drivers: the angle travelled since the last message (rectangle rule at
    // the new rate; a gap longer than max_velocity_gap is not bridged).
    if (last_velocity_stamp_) {
      const double dt = stamp - *last_velocity_stamp_;
      if (dt <= 0.0) {
        out.skipped = "stamp not newer than the last velocity message";
        return out;
      }
      if (dt <= config_.max_velocity_gap) {
        left_angle_ += *left * dt;
        right_angle_ += *right * dt;
      }
    }
    last_velocity_stamp_ = stamp;
  }
  s.left_ticks = to_ticks(left_angle_, config_.ticks_per_rev);
  s.right_ticks = to_ticks(right_angle_, config_.ticks_per_rev);
  out.sample = s;
  return out;
}

}  // namespace rownav::ros_bridge
