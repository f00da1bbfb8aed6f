#include "rownav/localize/wheel_odometry.hpp"

#include <cmath>
#include <numbers>

namespace rownav::localize {
namespace {
// The range of alpha a drive train can have: validate() and set_alpha() agree on it.
constexpr double kMinAlpha = 0.1, kMaxAlpha = 2.0;
}  // namespace

void WheelOdometryConfig::validate() const {
  core::check_positive(track_width, "track_width");
  core::check_positive(wheel_radius, "wheel_radius");
  core::check_positive(ticks_per_rev, "ticks_per_rev");
  core::check_positive(x_icr, "x_icr");
  core::check_range(alpha, kMinAlpha, kMaxAlpha, "alpha");
  core::check_positive(wheelbase, "wheelbase");
  core::check_positive(max_plausible_speed, "max_plausible_speed");
}

core::Pose2 twist_increment(const core::Twist2& t, double dt) {
  const double th = t.omega * dt;
  // SE(2) exponential: for a constant twist the body moves on an arc; the series form avoids
  // the 0/0 of straight motion.
  double a = 1.0, b = 0.5 * th;  // sin(th)/th, (1-cos(th))/th
  if (std::abs(th) > 1e-6) {
    a = std::sin(th) / th;
    b = (1.0 - std::cos(th)) / th;
  }
  const double dx = t.v * dt, dy = t.vy * dt;
  return {a * dx - b * dy, b * dx + a * dy, th};
}

WheelOdometry::WheelOdometry(const WheelOdometryConfig& config) : config_(config) {
  config_.validate();
}

void WheelOdometry::set_alpha(double alpha) {
  if (alpha >= kMinAlpha && alpha <= kMaxAlpha) config_.alpha = alpha;
}

core::Twist2 WheelOdometry::twist_from_wheels(double vl, double vr, double steering) const {
  core::Twist2 t;
  switch (config_.model) {
    case DriveModel::differential:  // ideal rolling without slip
      t.v = 0.5 * (vl + vr);
      t.omega = (vr - vl) / config_.track_width;
      break;
    case DriveModel::skid_steer:
      // Bertoglio 2023 eq. (1)-(2): v_x = alpha/2 (V_l + V_r), v_y = 0,
      // omega = alpha / (2 x_ICR) (V_r - V_l).
      t.v = 0.5 * config_.alpha * (vl + vr);
      t.omega = config_.alpha / (2.0 * config_.x_icr) * (vr - vl);
      break;
    case DriveModel::ackermann:
      // Bicycle model on the rear-axle centre: omega = v tan(delta) / L.
      t.v = 0.5 * config_.alpha * (vl + vr);
      t.omega = t.v * std::tan(steering) / config_.wheelbase;
      break;
  }
  return t;
}

std::optional<core::Twist2> WheelOdometry::add(const core::WheelEncoderSample& s) {
  if (!std::isfinite(s.stamp) || !std::isfinite(s.steering_angle)) {
    ++rejected_jumps_;
    return std::nullopt;
  }
  if (!last_) {
    last_ = s;
    return std::nullopt;
  }
  const double dt = s.stamp - last_->stamp;
  if (!(dt > 0.0)) {
    ++rejected_time_;
    return std::nullopt;
  }
  const double m_per_tick = 2.0 * std::numbers::pi * config_.wheel_radius / config_.ticks_per_rev;
  const double vl = static_cast<double>(s.left_ticks - last_->left_ticks) * m_per_tick / dt;
  const double vr = static_cast<double>(s.right_ticks - last_->right_ticks) * m_per_tick / dt;
  last_ = s;
  if (std::abs(vl) > config_.max_plausible_speed || std::abs(vr) > config_.max_plausible_speed) {
    ++rejected_jumps_;  // re-anchored on this sample: the glitch is not integrated
    return std::nullopt;
  }
  const core::Twist2 t = twist_from_wheels(vl, vr, s.steering_angle);
  pose_ = pose_ * twist_increment(t, dt);
  return t;
}

void WheelOdometry::reset(const core::Pose2& T_odom_base) {
  pose_ = T_odom_base;
  last_.reset();
}

}  // namespace rownav::localize
