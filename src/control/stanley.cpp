#include "rownav/control/stanley.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rownav/control/path_geometry.hpp"
#include "rownav/core/angle.hpp"

namespace rownav::control {

void StanleyConfig::validate() const {
  core::check_positive(k, "k");
  core::check_positive(softening_speed, "softening_speed");
  core::check_positive(yaw_gain, "yaw_gain");
  core::check_non_negative(yaw_gain_per_speed, "yaw_gain_per_speed");
  core::check_non_negative(wheelbase, "wheelbase");
  core::check(std::isfinite(front_axle_x), "front_axle_x", "must be finite");
  core::check_range(max_steer_deg, 1.0, 89.0, "max_steer_deg");
  core::validate_nested(slowdown, "slowdown");
}

StanleyController::StanleyController(const StanleyConfig& config)
    : config_((config.validate(), config)) {}

core::Twist2 StanleyController::compute(const ControlInput& in) {
  if (!input_finite(in)) return {};
  const double v = obstacle_limited_speed(in.speed_ref, in.obstacle_distance, config_.slowdown);
  const double theta_e = core::wrap_angle(in.heading_error);  // Lan 2021 eq. (15)
  // Cross-track error at the control point (front axle), left +.
  const double e = in.lateral_error + config_.front_axle_x * std::sin(theta_e);
  // Lan 2021 eq. (16); the steering that cancels both errors is its negative with e left +,
  // theta_e = robot minus path.
  const double speed = std::abs(std::isfinite(in.speed) && in.speed > 0.0 ? in.speed : v);
  const double delta_raw =
      -(theta_e + std::atan(config_.k * e / (speed + config_.softening_speed)));
  const double max_steer = config_.max_steer_deg * std::numbers::pi / 180.0;
  const double delta = std::clamp(delta_raw, -max_steer, max_steer);
  const double gain = std::max(config_.yaw_gain, config_.yaw_gain_per_speed * std::abs(v));
  const double omega =
      config_.wheelbase > 0.0 ? v * std::tan(delta) / config_.wheelbase : gain * delta;
  return {v, 0.0, omega};
}

}  // namespace rownav::control
