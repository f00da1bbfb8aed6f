#pragma once
/// @file velocity_limits.hpp Robot velocity, acceleration and curvature limits applied to a
/// controller's command (controllers do not apply them themselves; the caller does).
#include "rownav/core/config_fields.hpp"
#include "rownav/core/twist.hpp"

namespace rownav::control {

/// Limits of a robot base. Defaults: a small vineyard robot (Bertoglio 2023 sec. IV reached
/// 1 m/s in-row on the real robot).
struct VelocityLimits {
  double max_speed = 1.0;          ///< [m/s] forward speed limit (Bertoglio 2023 sec. IV)
  double max_reverse_speed = 0.3;  ///< [m/s] backward speed limit (magnitude)
  double max_yaw_rate = 1.0;       ///< [rad/s] |omega| limit
  double max_accel = 0.5;          ///< [m/s^2] |dv/dt| limit
  double max_yaw_accel = 2.0;      ///< [rad/s^2] |domega/dt| limit
  /// [m] smallest turning radius: |omega| <= |v| / min_turn_radius; 0 for robots that turn in
  /// place (skid steer, differential drive)
  double min_turn_radius = 0.0;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("max_speed", s.max_speed);
    v("max_reverse_speed", s.max_reverse_speed);
    v("max_yaw_rate", s.max_yaw_rate);
    v("max_accel", s.max_accel);
    v("max_yaw_accel", s.max_yaw_accel);
    v("min_turn_radius", s.min_turn_radius);
  }
  void validate() const;
};

/// Limits `cmd`: speed and yaw rate clamped, then the change from `previous` bounded by the
/// accelerations over `dt` [s] (dt <= 0 or non-finite: no acceleration limit), then the curvature
/// limit for car-like robots. Non-finite components of `cmd` become 0 (so do those of `previous`,
/// treated as a stop). vy is zeroed (the controllers command a unicycle). Never throws.
core::Twist2 apply_limits(const core::Twist2& cmd, const core::Twist2& previous, double dt,
                          const VelocityLimits& limits);

}  // namespace rownav::control
