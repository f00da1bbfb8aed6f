#pragma once
// A kinematic unicycle driven by a PathController along a straight (x-axis) or circular path,
// shared by the control tests. Ground truth is exact: the path is known in closed form.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "rownav/control/controller.hpp"
#include "rownav/control/velocity_limits.hpp"
#include "rownav/core/angle.hpp"

namespace rownav::control::test {

/// Path: the x-axis (radius = 0) or a circle of `radius` [m] turning left, tangent to the x-axis
/// at the origin (centre (0, radius)).
struct ClosedLoopResult {
  double final_abs_lateral = 0.0;  ///< [m] at the end
  double settle_time = -1.0;       ///< [s] from which |lateral| stays < 2 cm (-1: never)
  double overshoot = 0.0;          ///< [m] largest lateral on the side opposite the start
  double max_abs_omega = 0.0;      ///< [rad/s] largest raw command
  double min_speed = 1e9;          ///< [m/s] smallest raw forward command
};

/// Lateral (left +) and heading errors of pose (x, y, th) w.r.t. the path.
inline void path_errors(double radius, double x, double y, double th, double& e, double& he,
                        double& path_heading) {
  if (radius <= 0.0) {
    e = y;
    path_heading = 0.0;
  } else {
    const double dx = x, dy = y - radius;
    e = radius - std::hypot(dx, dy);  // inside the left turn = left of the path
    path_heading = std::atan2(dy, dx) + std::numbers::pi / 2.0;
  }
  he = core::wrap_angle(th - path_heading);
}

inline ClosedLoopResult run_closed_loop(PathController& c, double radius, double y0, double th0_rad,
                                        double duration, double speed_ref = 0.5, double dt = 0.1,
                                        const VelocityLimits& limits = {}) {
  ClosedLoopResult r;
  double x = 0.0, y = y0, th = th0_rad;
  core::Twist2 prev{speed_ref, 0.0, 0.0};  // already driving along the row
  const double start_sign = y0 >= 0.0 ? 1.0 : -1.0;
  for (double t = 0.0; t < duration; t += dt) {
    double e, he, ph;
    path_errors(radius, x, y, th, e, he, ph);
    if (std::abs(e) >= 0.02)
      r.settle_time = -1.0;
    else if (r.settle_time < 0.0)
      r.settle_time = t;
    r.overshoot = std::max(r.overshoot, -start_sign * e);
    ControlInput in;
    in.stamp = t;
    in.dt = dt;
    in.lateral_error = e;
    in.heading_error = he;
    // The path's tangent line in the base frame: through the foot of the robot on the path.
    const double c_ = std::cos(-he), s_ = std::sin(-he);
    in.path_base = core::Line2(Eigen::Vector2d(-e * -s_, -e * c_), Eigen::Vector2d(c_, s_));
    in.speed_ref = speed_ref;
    in.speed = prev.v;
    const core::Twist2 raw = c.compute(in);
    r.max_abs_omega = std::max(r.max_abs_omega, std::abs(raw.omega));
    r.min_speed = std::min(r.min_speed, raw.v);
    const core::Twist2 cmd = apply_limits(raw, prev, dt, limits);
    prev = cmd;
    // Exact unicycle integration over dt (constant twist).
    if (std::abs(cmd.omega) < 1e-9) {
      x += cmd.v * dt * std::cos(th);
      y += cmd.v * dt * std::sin(th);
    } else {
      const double th1 = th + cmd.omega * dt;
      x += cmd.v / cmd.omega * (std::sin(th1) - std::sin(th));
      y -= cmd.v / cmd.omega * (std::cos(th1) - std::cos(th));
    }
    th = core::wrap_angle(th + cmd.omega * dt);
  }
  double e, he, ph;
  path_errors(radius, x, y, th, e, he, ph);
  r.final_abs_lateral = std::abs(e);
  return r;
}

}  // namespace rownav::control::test
