#include "rownav/control/pure_pursuit.hpp"

#include <algorithm>
#include <cmath>

#include "rownav/control/path_geometry.hpp"

namespace rownav::control {

void PurePursuitConfig::validate() const {
  core::check_positive(min_lookahead, "min_lookahead");
  core::check_non_negative(lookahead_time, "lookahead_time");
  core::check(max_lookahead >= min_lookahead, "max_lookahead", "must be >= min_lookahead");
  core::check_non_negative(min_speed, "min_speed");
  core::validate_nested(slowdown, "slowdown");
}

PurePursuitController::PurePursuitController(const PurePursuitConfig& config)
    : config_((config.validate(), config)) {}

core::Twist2 PurePursuitController::compute(const ControlInput& in) {
  if (!input_finite(in)) return {};
  const double v = obstacle_limited_speed(in.speed_ref, in.obstacle_distance, config_.slowdown);
  const double speed = std::isfinite(in.speed) ? std::abs(in.speed) : std::abs(v);
  const double lookahead = std::clamp(config_.lookahead_time * std::max(speed, std::abs(v)),
                                      config_.min_lookahead, config_.max_lookahead);
  // The path point at distance `lookahead` from the robot along the path: the chord length L of
  // the arc, so kappa = 2 y / L^2 (Coulter 1992).
  const Eigen::Vector2d target = lookahead_point(in.path_base, lookahead);
  const double chord2 = std::max(target.squaredNorm(), 1e-6);
  const double kappa = 2.0 * target.y() / chord2;
  // Stopped (obstacle, zero reference): no turning on the spot either.
  const double v_kappa = v > 0.0 ? std::max(v, config_.min_speed) : v;
  return {v, 0.0, v_kappa * kappa};
}

}  // namespace rownav::control
