#pragma once
/// @file proprioception.hpp Simulated wheel encoders, IMU and GNSS from the true robot state.
#include <Eigen/Core>
#include <cstdint>
#include <random>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/sensor_samples.hpp"
#include "rownav/sim/ground_truth.hpp"
#include "rownav/sim/robot.hpp"

namespace rownav::sim {

/// Incremental wheel / track encoders (and the steering angle sensor of car-like robots).
struct EncoderConfig {
  int ticks_per_rev = 2048;         ///< [ticks/rev] of the wheel / sprocket
  double rate_hz = 50.0;            ///< [Hz] publication rate
  double steering_noise_deg = 0.1;  ///< [deg] std of the steering angle measurement

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("ticks_per_rev", s.ticks_per_rev);
    v("rate_hz", s.rate_hz);
    v("steering_noise_deg", s.steering_noise_deg);
  }
  void validate() const;
};

/// MEMS IMU: white noise plus a random-walk gyro bias (Allan-variance parameters).
struct ImuConfig {
  double rate_hz = 100.0;                 ///< [Hz]
  double gyro_noise_density = 2.0e-4;     ///< [rad/s/sqrt(Hz)] angle random walk
  double gyro_bias_std = 0.005;           ///< [rad/s] std of the turn-on bias
  double gyro_bias_random_walk = 2.0e-5;  ///< [rad/s/sqrt(s)] bias instability as a random walk
  double accel_noise_density = 2.0e-3;    ///< [m/s^2/sqrt(Hz)] velocity random walk
  double accel_bias_std = 0.02;           ///< [m/s^2] std of the turn-on accelerometer bias

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("rate_hz", s.rate_hz);
    v("gyro_noise_density", s.gyro_noise_density);
    v("gyro_bias_std", s.gyro_bias_std);
    v("gyro_bias_random_walk", s.gyro_bias_random_walk);
    v("accel_noise_density", s.accel_noise_density);
    v("accel_bias_std", s.accel_bias_std);
  }
  void validate() const;
};

/// GNSS receiver degraded under the canopy: inflated noise and outages in lanes.
struct GnssConfig {
  bool enabled = false;                     ///< false: every fix is invalid
  double rate_hz = 5.0;                     ///< [Hz]
  double noise_std = 0.02;                  ///< [m] horizontal 1-sigma in the open (RTK fix)
  double outage_probability_in_lane = 0.1;  ///< [1/s] rate at which outages start in a lane
  double outage_mean_duration = 5.0;        ///< [s] mean (exponential) outage length
  double canopy_noise_factor = 5.0;         ///< [-] noise multiplier in a lane (under the canopy)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("enabled", s.enabled);
    v("rate_hz", s.rate_hz);
    v("noise_std", s.noise_std);
    v("outage_probability_in_lane", s.outage_probability_in_lane);
    v("outage_mean_duration", s.outage_mean_duration);
    v("canopy_noise_factor", s.canopy_noise_factor);
  }
  void validate() const;
};

/// Quantised cumulative encoder counts of the true wheel angles.
class WheelEncoders {
 public:
  WheelEncoders(const EncoderConfig& config, std::uint64_t seed);
  /// ticks = floor(wheel_angle / 2 pi * ticks_per_rev); steering angle with noise.
  core::WheelEncoderSample sample(const RobotState& state);
  const EncoderConfig& config() const { return config_; }

 private:
  EncoderConfig config_;
  std::mt19937_64 rng_;
};

/// Body-frame IMU at the base_link origin.
class Imu {
 public:
  Imu(const ImuConfig& config, std::uint64_t seed);
  /// Gyro: true body rate (yaw rate projected by roll / pitch) + bias + white noise.
  /// Accelerometer: true body acceleration (from the twist change since the previous sample,
  /// including the centripetal term) + gravity projected by roll / pitch [rad] + noise.
  core::ImuSample sample(const RobotState& state, double roll, double pitch);
  /// [rad/s] current gyro bias (ground truth for tests / calibration).
  const Eigen::Vector3d& gyro_bias() const { return gyro_bias_; }
  const ImuConfig& config() const { return config_; }

 private:
  ImuConfig config_;
  std::mt19937_64 rng_;
  Eigen::Vector3d gyro_bias_, accel_bias_;
  core::Twist2 last_twist_;
  double last_stamp_ = 0.0;
  bool has_last_ = false;
};

/// GNSS fixes in the field's ENU frame.
class Gnss {
 public:
  Gnss(const GnssConfig& config, std::uint64_t seed);
  /// Fix for the true antenna position [m]; outages start only in a lane and end on leaving it.
  core::GnssFix sample(double stamp, const Eigen::Vector3d& position_enu, Place place);
  bool in_outage() const { return outage_; }
  const GnssConfig& config() const { return config_; }

 private:
  GnssConfig config_;
  std::mt19937_64 rng_;
  double last_stamp_ = 0.0;
  bool has_last_ = false;
  bool outage_ = false;
  double outage_end_ = 0.0;  // [s]
};

}  // namespace rownav::sim
