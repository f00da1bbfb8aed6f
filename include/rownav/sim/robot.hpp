#pragma once
/// @file robot.hpp Simulated ground robots: differential, skid-steer (ICR model) and car-like.
///
/// Commands are converted to wheel / track speeds with the NOMINAL (ideal) inverse kinematics a
/// robot's firmware uses, while the body moves with the TRUE kinematics (Bertoglio 2023,
/// 003_25dc0df51a1e5faf.txt sec. II-A, eq. (1)-(2)) plus filtered slip noise, so wheel odometry
/// with nominal parameters drifts as it does on a real robot.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/core/robot_spec.hpp"
#include "rownav/core/twist.hpp"

namespace rownav::sim {

/// Drive kinematics (the core's: a robot file names it).
using DriveKind = core::DriveKind;

/// A simulated robot: the nominal geometry and limits every robot file gives
/// (core::RobotSpec, what the stack knows) plus the TRUE kinematics the simulator moves the body
/// with, unknown to the stack.
struct RobotConfig : core::RobotSpec {
  double x_icr = 0.40;  ///< [m] true ICR distance, Bertoglio 2023 eq. (2) (ideal: track_width / 2)
  double alpha = 0.90;  ///< [-] true correction factor, Bertoglio 2023 eq. (2) (ideal: 1)
  double slip_noise = 0.02;         ///< [-] std of the relative random track-speed slip
  double slip_time_constant = 0.5;  ///< [s] low-pass time constant of the slip noise

  template <class S, class V>
  static void fields(S& s, V& v) {
    core::RobotSpec::fields(s, v);
    simulation_fields(s, v);
  }
  /// The keys the simulator adds to a robot file (a robot file read as core::RobotSpec skips
  /// them: io::kSimulatorRobotKeys, tested against this list).
  template <class S, class V>
  static void simulation_fields(S& s, V& v) {
    v("x_icr", s.x_icr);
    v("alpha", s.alpha);
    v("slip_noise", s.slip_noise);
    v("slip_time_constant", s.slip_time_constant);
  }
  void validate() const;
};

/// True state of a simulated robot.
struct RobotState {
  double stamp = 0.0;              ///< [s]
  core::Pose2 pose;                ///< true planar pose T_world_base
  core::Twist2 twist;              ///< true body velocity
  double left_wheel_speed = 0.0;   ///< [rad/s] left wheel / sprocket (rear-left for ackermann)
  double right_wheel_speed = 0.0;  ///< [rad/s]
  double left_wheel_angle = 0.0;   ///< [rad] cumulative
  double right_wheel_angle = 0.0;  ///< [rad] cumulative
  double steering_angle = 0.0;     ///< [rad] ackermann front wheel (bicycle model)
};

/// A simulated robot integrating commanded twists.
class Robot {
 public:
  /// Validates `config` (throws std::invalid_argument naming the field).
  Robot(const RobotConfig& config, std::uint64_t seed, const core::Pose2& start,
        double stamp = 0.0);

  /// Applies a commanded body twist for dt [s]: clamps it to the speed / yaw-rate / acceleration
  /// limits (steering angle / rate for ackermann), converts it to wheel speeds with the nominal
  /// kinematics (x_icr = track / 2, alpha = 1) and integrates the true motion (ICR model with the
  /// true x_icr / alpha and slip noise). NaN commands count as zero; dt <= 0 is ignored.
  const RobotState& step(const core::Twist2& cmd, double dt);

  const RobotState& state() const { return state_; }
  const RobotConfig& config() const { return config_; }
  /// Puts the robot at `T_world_base` without its wheels turning, as a push, a hand or a tow
  /// moves it (Simulator::carry): the wheel angles and speeds and the twist are kept, so the
  /// encoders and the IMU do not see the move.
  void place(const core::Pose2& T_world_base) { state_.pose = T_world_base; }
  /// Footprint rectangle corners in the world frame (counter-clockwise).
  std::array<Eigen::Vector2d, 4> footprint_world() const;

 private:
  core::Twist2 limit(const core::Twist2& cmd, double dt);
  void step_tracks(double dt);
  void step_ackermann(double dt);
  void update_slip(double dt);
  void integrate(double dt);

  RobotConfig config_;
  RobotState state_;
  std::mt19937_64 rng_;
  core::Twist2 applied_;  // rate-limited command
  double slip_left_ = 0.0, slip_right_ = 0.0;
};

}  // namespace rownav::sim
