#include "rownav/control/lookahead_pid.hpp"

#include <cmath>

#include "rownav/control/path_geometry.hpp"

namespace rownav::control {

void LookaheadPidConfig::validate() const {
  core::check_positive(lookahead, "lookahead");
  core::validate_nested(pid, "pid");
  core::validate_nested(slowdown, "slowdown");
}

LookaheadPidController::LookaheadPidController(const LookaheadPidConfig& config)
    : config_((config.validate(), config)), pid_(config.pid) {}

core::Twist2 LookaheadPidController::compute(const ControlInput& in) {
  if (!input_finite(in)) return {};
  const Eigen::Vector2d target = lookahead_point(in.path_base, config_.lookahead);
  // Bearing of the navigation point from the robot centre line (Bertoglio sec. II-B, Fig. 4).
  const double bearing = std::atan2(target.y(), target.x());
  const double omega = pid_.update(bearing, in.dt);
  const double v = obstacle_limited_speed(in.speed_ref, in.obstacle_distance, config_.slowdown);
  return {v, 0.0, omega};
}

}  // namespace rownav::control
