#include "rownav/control/pid.hpp"

#include <algorithm>
#include <cmath>

namespace rownav::control {

void PidGains::validate() const {
  core::check_non_negative(kp, "kp");
  core::check_non_negative(ki, "ki");
  core::check_non_negative(kd, "kd");
  core::check_non_negative(integral_limit, "integral_limit");
}

double Pid::update(double error, double dt) {
  if (!std::isfinite(error)) return 0.0;
  if (!std::isfinite(dt) || dt <= 0.0) return gains_.kp * error;
  integral_ = std::clamp(integral_ + error * dt, -gains_.integral_limit, gains_.integral_limit);
  const double derivative = has_previous_ ? (error - previous_) / dt : 0.0;
  previous_ = error;
  has_previous_ = true;
  return gains_.kp * error + gains_.ki * integral_ + gains_.kd * derivative;
}

void Pid::reset() {
  integral_ = 0.0;
  previous_ = 0.0;
  has_previous_ = false;
}

}  // namespace rownav::control
