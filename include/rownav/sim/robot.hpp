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
#include "rownav/core/twist.hpp"

namespace rownav::sim {

/// Drive kinematics.
enum class DriveKind : std::uint8_t { differential, skid_steer, ackermann };

/// Geometry, true kinematic parameters and limits of a robot.
struct RobotConfig {
  DriveKind drive = DriveKind::skid_steer;  ///< kinematic model
  std::string name = "skid_steer";          ///< label for reports
  double track_width = 0.55;                ///< [m] wheel / track centre distance
  double wheelbase = 0.6;                   ///< [m] ackermann: rear to front axle
  double wheel_radius = 0.165;              ///< [m] (track: sprocket radius)
  double x_icr = 0.40;  ///< [m] true ICR distance, Bertoglio 2023 eq. (2) (ideal: track_width / 2)
  double alpha = 0.90;  ///< [-] true correction factor, Bertoglio 2023 eq. (2) (ideal: 1)
  double slip_noise = 0.02;          ///< [-] std of the relative random track-speed slip
  double slip_time_constant = 0.5;   ///< [s] low-pass time constant of the slip noise
  double max_speed = 1.5;            ///< [m/s] forward
  double max_reverse_speed = 0.5;    ///< [m/s] backward (positive number)
  double max_yaw_rate = 1.5;         ///< [rad/s]
  double max_accel = 1.0;            ///< [m/s^2] |dv/dt| of the commanded speed
  double max_yaw_accel = 3.0;        ///< [rad/s^2] |domega/dt| of the commanded yaw rate
  double max_steer_deg = 35.0;       ///< [deg] ackermann: min turn radius = wheelbase / tan(this)
  double max_steer_rate_deg = 60.0;  ///< [deg/s] ackermann steering rate
  double length = 0.9;               ///< [m] body footprint length
  double width = 0.6;                ///< [m] body footprint width
  double base_to_front = 0.45;       ///< [m] base_link to the front of the footprint

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("drive", s.drive);
    v("name", s.name);
    v("track_width", s.track_width);
    v("wheelbase", s.wheelbase);
    v("wheel_radius", s.wheel_radius);
    v("x_icr", s.x_icr);
    v("alpha", s.alpha);
    v("slip_noise", s.slip_noise);
    v("slip_time_constant", s.slip_time_constant);
    v("max_speed", s.max_speed);
    v("max_reverse_speed", s.max_reverse_speed);
    v("max_yaw_rate", s.max_yaw_rate);
    v("max_accel", s.max_accel);
    v("max_yaw_accel", s.max_yaw_accel);
    v("max_steer_deg", s.max_steer_deg);
    v("max_steer_rate_deg", s.max_steer_rate_deg);
    v("length", s.length);
    v("width", s.width);
    v("base_to_front", s.base_to_front);
  }
  void validate() const;
  /// [m] smallest turn radius: wheelbase / tan(max_steer) for ackermann, 0 otherwise.
  double min_turn_radius() const;
  /// True for robots that can rotate on the spot (differential, skid-steer).
  bool can_turn_in_place() const { return drive != DriveKind::ackermann; }
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

template <>
struct rownav::core::EnumNames<rownav::sim::DriveKind> {
  using E = rownav::sim::DriveKind;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::differential, "differential"},
       {E::skid_steer, "skid_steer"},
       {E::ackermann, "ackermann"}}};
};
