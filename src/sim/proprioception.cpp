#include "rownav/sim/proprioception.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rownav/core/angle.hpp"

namespace rownav::sim {
namespace {

constexpr double kGravity = 9.80665;  // [m/s^2]

Eigen::Vector3d gaussian3(std::mt19937_64& rng, double std) {
  std::normal_distribution<double> n(0.0, 1.0);
  const double a = n(rng), b = n(rng), c = n(rng);
  return std * Eigen::Vector3d(a, b, c);
}

/// World z axis expressed in the body frame for roll / pitch (ZYX Euler, REP 103).
Eigen::Vector3d up_in_body(double roll, double pitch) {
  return {-std::sin(pitch), std::sin(roll) * std::cos(pitch), std::cos(roll) * std::cos(pitch)};
}

std::int64_t ticks(double angle, int ticks_per_rev) {
  return static_cast<std::int64_t>(std::floor(angle / (2.0 * std::numbers::pi) * ticks_per_rev));
}

}  // namespace

void EncoderConfig::validate() const {
  core::check_positive(ticks_per_rev, "ticks_per_rev");
  core::check_positive(rate_hz, "rate_hz");
  core::check_non_negative(steering_noise_deg, "steering_noise_deg");
}

void ImuConfig::validate() const {
  core::check_positive(rate_hz, "rate_hz");
  core::check_non_negative(gyro_noise_density, "gyro_noise_density");
  core::check_non_negative(gyro_bias_std, "gyro_bias_std");
  core::check_non_negative(gyro_bias_random_walk, "gyro_bias_random_walk");
  core::check_non_negative(accel_noise_density, "accel_noise_density");
  core::check_non_negative(accel_bias_std, "accel_bias_std");
}

void GnssConfig::validate() const {
  core::check_positive(rate_hz, "rate_hz");
  core::check_non_negative(noise_std, "noise_std");
  core::check_non_negative(outage_probability_in_lane, "outage_probability_in_lane");
  core::check_positive(outage_mean_duration, "outage_mean_duration");
  core::check(canopy_noise_factor >= 1.0, "canopy_noise_factor", "must be >= 1");
}

WheelEncoders::WheelEncoders(const EncoderConfig& config, std::uint64_t seed)
    : config_(config), rng_(seed) {
  config_.validate();
}

core::WheelEncoderSample WheelEncoders::sample(const RobotState& state) {
  core::WheelEncoderSample s;
  s.stamp = state.stamp;
  s.left_ticks = ticks(state.left_wheel_angle, config_.ticks_per_rev);
  s.right_ticks = ticks(state.right_wheel_angle, config_.ticks_per_rev);
  std::normal_distribution<double> n(0.0, core::deg2rad(config_.steering_noise_deg));
  s.steering_angle = state.steering_angle + n(rng_);
  return s;
}

Imu::Imu(const ImuConfig& config, std::uint64_t seed) : config_(config), rng_(seed) {
  config_.validate();
  gyro_bias_ = gaussian3(rng_, config_.gyro_bias_std);
  accel_bias_ = gaussian3(rng_, config_.accel_bias_std);
}

core::ImuSample Imu::sample(const RobotState& state, double roll, double pitch) {
  double dt = has_last_ ? state.stamp - last_stamp_ : 0.0;
  if (!(dt > 0.0) || !std::isfinite(dt)) dt = 0.0;
  const auto& t = state.twist;
  Eigen::Vector3d a_body = Eigen::Vector3d::Zero();
  if (dt > 0.0) {
    // Body-frame acceleration of a planar rigid body: dv/dt - omega x v.
    a_body.x() = (t.v - last_twist_.v) / dt - t.omega * t.vy;
    a_body.y() = (t.vy - last_twist_.vy) / dt + t.omega * t.v;
    // Bias random walk: variance grows with elapsed time.
    gyro_bias_ += gaussian3(rng_, config_.gyro_bias_random_walk * std::sqrt(dt));
  }
  if (!std::isfinite(roll)) roll = 0.0;
  if (!std::isfinite(pitch)) pitch = 0.0;
  const Eigen::Vector3d up = up_in_body(roll, pitch);
  // Discrete white noise std = density * sqrt(sample rate).
  const double sq = std::sqrt(config_.rate_hz);
  core::ImuSample s;
  s.stamp = state.stamp;
  s.angular_velocity = t.omega * up + gyro_bias_ + gaussian3(rng_, config_.gyro_noise_density * sq);
  s.linear_acceleration =
      a_body + kGravity * up + accel_bias_ + gaussian3(rng_, config_.accel_noise_density * sq);
  last_twist_ = t;
  last_stamp_ = state.stamp;
  has_last_ = true;
  return s;
}

Gnss::Gnss(const GnssConfig& config, std::uint64_t seed) : config_(config), rng_(seed) {
  config_.validate();
}

core::GnssFix Gnss::sample(double stamp, const Eigen::Vector3d& position_enu, Place place) {
  core::GnssFix fix;
  fix.stamp = stamp;
  const double dt = has_last_ ? std::max(0.0, stamp - last_stamp_) : 1.0 / config_.rate_hz;
  last_stamp_ = stamp;
  has_last_ = true;
  const bool lane = place == Place::lane;
  if (outage_ && (!lane || stamp >= outage_end_)) outage_ = false;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double p_start = 1.0 - std::exp(-config_.outage_probability_in_lane * dt);
  const double draw = u(rng_);  // drawn every sample so the stream does not depend on the place
  if (!outage_ && lane && draw < p_start) {
    std::exponential_distribution<double> e(1.0 / config_.outage_mean_duration);
    outage_ = true;
    outage_end_ = stamp + e(rng_);
  }
  if (!config_.enabled || outage_ || !position_enu.allFinite()) return fix;
  const double std = config_.noise_std * (lane ? config_.canopy_noise_factor : 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  const double ex = n(rng_), ey = n(rng_), ez = n(rng_);
  fix.valid = true;
  fix.horizontal_std = std;
  fix.position_enu = position_enu + Eigen::Vector3d(std * ex, std * ey, 2.0 * std * ez);
  return fix;
}

}  // namespace rownav::sim
