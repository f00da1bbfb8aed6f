#pragma once
/// @file robot_spec.hpp What the navigation stack knows of the robot it drives: drive kind,
/// NOMINAL geometry, limits and footprint. A robot file (config/robots/*.yaml) holds these keys;
/// the simulator's robot (sim::RobotConfig) adds its true kinematics to them, so the ROS node and
/// any embedding program read a robot without linking the simulator (issue 14).
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"

namespace rownav::core {

/// Drive kinematics.
enum class DriveKind : std::uint8_t { differential, skid_steer, ackermann };

/// Geometry and limits of a robot, as its base controller and the stack use them.
struct RobotSpec {
  DriveKind drive = DriveKind::skid_steer;  ///< kinematic model
  std::string name = "skid_steer";          ///< label for reports
  double track_width = 0.55;                ///< [m] wheel / track centre distance
  double wheelbase = 0.6;                   ///< [m] ackermann: rear to front axle
  double wheel_radius = 0.165;              ///< [m] (track: sprocket radius)
  double max_speed = 1.5;                   ///< [m/s] forward
  double max_reverse_speed = 0.5;           ///< [m/s] backward (positive number)
  double max_yaw_rate = 1.5;                ///< [rad/s]
  double max_accel = 1.0;                   ///< [m/s^2] |dv/dt| of the commanded speed
  double max_yaw_accel = 3.0;               ///< [rad/s^2] |domega/dt| of the commanded yaw rate
  double max_steer_deg = 35.0;       ///< [deg] ackermann: min turn radius = wheelbase / tan(this)
  double max_steer_rate_deg = 60.0;  ///< [deg/s] ackermann steering rate
  double length = 0.9;               ///< [m] body footprint length
  double width = 0.6;                ///< [m] body footprint width
  double base_to_front = 0.45;       ///< [m] base_link to the front of the footprint
  /// [m] the ICR distance x_ICR the robot's wheel odometry assumes, as calibrated on the robot
  /// (Bertoglio 2023 eq. (2)); 0: the nominal track_width / 2 (skid-steer only)
  double odometry_x_icr = 0.0;
  /// [-] the correction factor alpha the wheel odometry assumes, as calibrated on the robot
  /// (Bertoglio 2023 eq. (2)); 1: nominal (skid-steer only)
  double odometry_alpha = 1.0;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("drive", s.drive);
    v("name", s.name);
    v("track_width", s.track_width);
    v("wheelbase", s.wheelbase);
    v("wheel_radius", s.wheel_radius);
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
    v("odometry_x_icr", s.odometry_x_icr);
    v("odometry_alpha", s.odometry_alpha);
  }
  void validate() const;
  /// [m] smallest turn radius: wheelbase / tan(max_steer) for ackermann, 0 otherwise.
  double min_turn_radius() const;
  /// True for robots that can rotate on the spot (differential, skid-steer).
  bool can_turn_in_place() const { return drive != DriveKind::ackermann; }
};

}  // namespace rownav::core

template <>
struct rownav::core::EnumNames<rownav::core::DriveKind> {
  using E = rownav::core::DriveKind;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::differential, "differential"},
       {E::skid_steer, "skid_steer"},
       {E::ackermann, "ackermann"}}};
};
