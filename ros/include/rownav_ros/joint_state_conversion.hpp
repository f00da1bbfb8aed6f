#pragma once
/// @file joint_state_conversion.hpp sensor_msgs/JointState (a robot's wheel joints) ->
/// core::WheelEncoderSample, so that NavStack runs its own wheel odometry + IMU EKF on a robot
/// that publishes joint states instead of nav_msgs/Odometry (issue 15). Wheel positions are
/// joint angles in radians (REP 103 / sensor_msgs convention for continuous joints); several
/// joints on one side (a skid-steer's front and rear wheels) are averaged, as the tracks of a
/// skid-steer model are. A driver that publishes only velocities is integrated over the stamps.
#include <sensor_msgs/JointState.h>

#include <optional>
#include <string>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/sensor_samples.hpp"

namespace rownav::ros_bridge {

/// Which joints are the wheels (rownav_node's ~wheels/... parameters).
struct WheelJointConfig {
  /// left wheel joints (skid-steer: every wheel of the side, averaged); the defaults are the
  /// names of Clearpath's and most diff-drive URDFs
  std::vector<std::string> left_joints{"left_wheel_joint"};
  std::vector<std::string> right_joints{"right_wheel_joint"};  ///< right wheel joints
  /// car-like robots: the front steering joint (its position is the bicycle-model steering
  /// angle, rad); empty: none
  std::string steering_joint;
  /// [ticks/rev] resolution at which joint angles are handed to the stack's wheel odometry
  /// (core::WheelEncoderSample counts ticks): fine enough that the rounding (2 pi / 2^16 rad,
  /// 16 um of a 0.165 m wheel) is far below any wheel encoder's own (rownav)
  int ticks_per_rev = 65536;
  /// [s] a velocity-only message more than this after the previous one is not integrated
  /// across the gap (the wheels' travel in it is unknown): the integration restarts (rownav)
  double max_velocity_gap = 0.5;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("left_joints", s.left_joints);
    v("right_joints", s.right_joints);
    v("steering_joint", s.steering_joint);
    v("ticks_per_rev", s.ticks_per_rev);
    v("max_velocity_gap", s.max_velocity_gap);
  }
  void validate() const;
};

/// One converted message.
struct JointConversion {
  std::optional<core::WheelEncoderSample> sample;  ///< nullopt: not a wheel message, or bad
  std::string skipped;                             ///< empty, or why no sample came out (one line)
};

/// Wheel counts of `ticks_per_rev` as the JointState a base driver publishes: the first left and
/// right joint of `joints` at angle 2 pi ticks / ticks_per_rev [rad], the steering joint (when
/// named) at the steering angle. The inverse of JointStateConverter::convert for the same
/// resolution (the simulator node, tests).
sensor_msgs::JointState to_joint_state_msg(const core::WheelEncoderSample& s, int ticks_per_rev,
                                           const WheelJointConfig& joints);

/// Converts JointState messages into cumulative wheel counts. Never throws after construction.
class JointStateConverter {
 public:
  /// Validates `config` (std::invalid_argument naming the field).
  explicit JointStateConverter(const WheelJointConfig& config);

  /// A message that names none of the wheel joints (another joint group published on the same
  /// topic) is skipped quietly (`skipped` says so); one that names only some of them, or gives
  /// a non-finite position / velocity, or neither positions nor velocities, is skipped with the
  /// reason. Positions win over velocities when a message has both.
  JointConversion convert(const sensor_msgs::JointState& msg);

 private:
  std::optional<double> mean_of(const sensor_msgs::JointState& msg,
                                const std::vector<std::string>& joints, bool positions,
                                std::string& why) const;

  WheelJointConfig config_;
  // [rad] mean joint angle of each side (integrated for velocity-only drivers)
  double left_angle_ = 0.0, right_angle_ = 0.0;
  std::optional<double> last_velocity_stamp_;  // [s] of the last velocity-only message
};

}  // namespace rownav::ros_bridge
