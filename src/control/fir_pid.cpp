#include "rownav/control/fir_pid.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "rownav/control/path_geometry.hpp"
#include "rownav/core/angle.hpp"

namespace rownav::control {

void FirPidConfig::validate() const {
  core::check(!fir.empty() && fir.size() <= 64, "fir", "must hold 1 to 64 coefficients");
  for (double b : fir) core::check(std::isfinite(b), "fir", "coefficients must be finite");
  const double sum = std::accumulate(fir.begin(), fir.end(), 0.0);
  core::check(std::abs(sum) > 1e-9, "fir", "coefficients must not sum to 0");
  core::validate_nested(pid, "pid");
  core::check_non_negative(steep_threshold, "steep_threshold");
  core::check_non_negative(steep_preview, "steep_preview");
  core::check_range(steep_speed_scale, 0.0, 1.0, "steep_speed_scale");
  core::check_positive(steep_max_omega, "steep_max_omega");
  core::validate_nested(slowdown, "slowdown");
}

FirPidController::FirPidController(const FirPidConfig& config)
    : config_((config.validate(), config)), b_(config.fir), pid_(config.pid) {
  // Unit DC gain: a constant error passes unchanged, so the PID gains keep their meaning.
  const double sum = std::accumulate(b_.begin(), b_.end(), 0.0);
  for (double& b : b_) b /= sum;
}

void FirPidController::reset() {
  taps_.clear();
  pid_.reset();
}

double FirPidController::filter(double error) {
  // Malavazi 2018 eq. (6); until N past errors exist the oldest one stands for the missing ones.
  taps_.push_front(error);
  while (taps_.size() > b_.size()) taps_.pop_back();
  double out = 0.0;
  for (std::size_t i = 0; i < b_.size(); ++i) out += b_[i] * taps_[std::min(i, taps_.size() - 1)];
  return out;
}

core::Twist2 FirPidController::compute(const ControlInput& in) {
  if (!input_finite(in)) return {};
  double v = obstacle_limited_speed(in.speed_ref, in.obstacle_distance, config_.slowdown);
  const bool steep = std::isfinite(in.steepness) && in.steepness > config_.steep_threshold;
  // Pre-control (sec. 2.3.3): distance to the target; steep models: where the heading leads.
  double error = in.lateral_error;
  if (steep) error += config_.steep_preview * std::sin(core::wrap_angle(in.heading_error));
  const double filtered = filter(error);
  // PID (sec. 2.3.5): a left error (+) needs a right turn (omega < 0).
  double omega = -pid_.update(filtered, in.dt);
  if (steep) {
    v *= config_.steep_speed_scale;
    omega = std::clamp(omega, -config_.steep_max_omega, config_.steep_max_omega);
  }
  return {v, 0.0, omega};
}

}  // namespace rownav::control
