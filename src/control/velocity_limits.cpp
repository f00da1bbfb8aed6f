#include "rownav/control/velocity_limits.hpp"

#include <algorithm>
#include <cmath>

namespace rownav::control {

namespace {

double finite_or_zero(double x) {
  return std::isfinite(x) ? x : 0.0;
}

// Moves `from` towards `to` by at most `step`.
double rate_limit(double to, double from, double step) {
  return std::clamp(to, from - step, from + step);
}

}  // namespace

void VelocityLimits::validate() const {
  core::check_positive(max_speed, "max_speed");
  core::check_non_negative(max_reverse_speed, "max_reverse_speed");
  core::check_positive(max_yaw_rate, "max_yaw_rate");
  core::check_positive(max_accel, "max_accel");
  core::check_positive(max_yaw_accel, "max_yaw_accel");
  core::check_non_negative(min_turn_radius, "min_turn_radius");
}

core::Twist2 apply_limits(const core::Twist2& cmd, const core::Twist2& previous, double dt,
                          const VelocityLimits& limits) {
  double v = std::clamp(finite_or_zero(cmd.v), -limits.max_reverse_speed, limits.max_speed);
  double w = std::clamp(finite_or_zero(cmd.omega), -limits.max_yaw_rate, limits.max_yaw_rate);
  if (std::isfinite(dt) && dt > 0.0) {
    v = rate_limit(v, finite_or_zero(previous.v), limits.max_accel * dt);
    w = rate_limit(w, finite_or_zero(previous.omega), limits.max_yaw_accel * dt);
    // A previous command beyond the limits (limits changed) must not keep the robot beyond them.
    v = std::clamp(v, -limits.max_reverse_speed, limits.max_speed);
    w = std::clamp(w, -limits.max_yaw_rate, limits.max_yaw_rate);
  }
  // Car-like robots cannot turn tighter than their minimum radius: kappa = omega / v.
  if (limits.min_turn_radius > 0.0) {
    const double w_max = std::abs(v) / limits.min_turn_radius;
    w = std::clamp(w, -w_max, w_max);
  }
  return {v, 0.0, w};
}

}  // namespace rownav::control
