#include "rownav/sim/robot.hpp"

#include <algorithm>
#include <cmath>

#include "rownav/core/angle.hpp"

namespace rownav::sim {
namespace {

double finite_or_zero(double x) {
  return std::isfinite(x) ? x : 0.0;
}

/// Moves `current` towards `target` by at most `max_step`.
double rate_limit(double current, double target, double max_step) {
  return current + std::clamp(target - current, -max_step, max_step);
}

}  // namespace

void RobotConfig::validate() const {
  core::RobotSpec::validate();
  core::check_positive(x_icr, "x_icr");
  core::check_range(alpha, 0.1, 1.5, "alpha");
  core::check_range(slip_noise, 0.0, 0.5, "slip_noise");
  core::check_positive(slip_time_constant, "slip_time_constant");
}

Robot::Robot(const RobotConfig& config, std::uint64_t seed, const core::Pose2& start, double stamp)
    : config_(config), rng_(seed) {
  config_.validate();
  state_.pose = start;
  state_.stamp = stamp;
}

core::Twist2 Robot::limit(const core::Twist2& cmd, double dt) {
  const double v = std::clamp(finite_or_zero(cmd.v), -config_.max_reverse_speed, config_.max_speed);
  const double w =
      std::clamp(finite_or_zero(cmd.omega), -config_.max_yaw_rate, config_.max_yaw_rate);
  applied_.v = rate_limit(applied_.v, v, config_.max_accel * dt);
  applied_.omega = rate_limit(applied_.omega, w, config_.max_yaw_accel * dt);
  applied_.vy = 0.0;
  return applied_;
}

void Robot::update_slip(double dt) {
  // First-order Gauss-Markov process: stationary std = slip_noise, correlation time tau.
  const double a = std::exp(-dt / config_.slip_time_constant);
  const double b = config_.slip_noise * std::sqrt(1.0 - a * a);
  std::normal_distribution<double> n(0.0, 1.0);
  slip_left_ = a * slip_left_ + b * n(rng_);
  slip_right_ = a * slip_right_ + b * n(rng_);
}

void Robot::step_tracks(double dt) {
  const double half = 0.5 * config_.track_width;
  // Nominal inverse kinematics: what the motor controllers are asked to do.
  const double vl = applied_.v - applied_.omega * half;
  const double vr = applied_.v + applied_.omega * half;
  state_.left_wheel_speed = vl / config_.wheel_radius;
  state_.right_wheel_speed = vr / config_.wheel_radius;
  update_slip(dt);
  const double gl = vl * (1.0 + slip_left_), gr = vr * (1.0 + slip_right_);
  // True motion, Bertoglio 2023 eq. (1)-(2): v_x = alpha/2 (V_l + V_r), v_y = 0,
  // omega = alpha / (2 x_ICR) (V_r - V_l).
  state_.twist.v = 0.5 * config_.alpha * (gl + gr);
  state_.twist.vy = 0.0;
  state_.twist.omega = config_.alpha / (2.0 * config_.x_icr) * (gr - gl);
}

void Robot::step_ackermann(double dt) {
  const double max_steer = core::deg2rad(config_.max_steer_deg);
  double target = state_.steering_angle;  // keep the wheel where it is when (nearly) stopped
  if (std::abs(applied_.v) > 1e-3)
    target = std::atan(config_.wheelbase * applied_.omega / applied_.v);
  target = std::clamp(target, -max_steer, max_steer);
  state_.steering_angle =
      rate_limit(state_.steering_angle, target, core::deg2rad(config_.max_steer_rate_deg) * dt);
  // Rear wheels follow the bicycle model with the actual steering angle.
  const double w_nom = applied_.v * std::tan(state_.steering_angle) / config_.wheelbase;
  const double half = 0.5 * config_.track_width;
  state_.left_wheel_speed = (applied_.v - w_nom * half) / config_.wheel_radius;
  state_.right_wheel_speed = (applied_.v + w_nom * half) / config_.wheel_radius;
  update_slip(dt);
  const double v = config_.alpha * applied_.v * (1.0 + 0.5 * (slip_left_ + slip_right_));
  state_.twist.v = v;
  state_.twist.vy = 0.0;
  state_.twist.omega = v * std::tan(state_.steering_angle) / config_.wheelbase;
}

void Robot::integrate(double dt) {
  // Midpoint rule on the heading: exact enough for dt <= 0.05 s at field speeds.
  const auto& t = state_.twist;
  const double th = state_.pose.theta + 0.5 * t.omega * dt;
  const double c = std::cos(th), s = std::sin(th);
  state_.pose =
      core::Pose2(state_.pose.x + (c * t.v - s * t.vy) * dt,
                  state_.pose.y + (s * t.v + c * t.vy) * dt, state_.pose.theta + t.omega * dt);
  state_.left_wheel_angle += state_.left_wheel_speed * dt;
  state_.right_wheel_angle += state_.right_wheel_speed * dt;
  state_.stamp += dt;
}

const RobotState& Robot::step(const core::Twist2& cmd, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) return state_;
  // Long steps are split so the rate limits and the midpoint rule stay accurate.
  const int n = static_cast<int>(std::clamp(std::ceil(dt / 0.02), 1.0, 1000.0));
  const double h = dt / n;
  for (int i = 0; i < n; ++i) {
    limit(cmd, h);
    if (config_.drive == DriveKind::ackermann)
      step_ackermann(h);
    else
      step_tracks(h);
    integrate(h);
  }
  return state_;
}

std::array<Eigen::Vector2d, 4> Robot::footprint_world() const {
  const double f = config_.base_to_front, r = f - config_.length, w = 0.5 * config_.width;
  const auto& T = state_.pose;
  return {T * Eigen::Vector2d(r, -w), T * Eigen::Vector2d(f, -w), T * Eigen::Vector2d(f, w),
          T * Eigen::Vector2d(r, w)};
}

}  // namespace rownav::sim
