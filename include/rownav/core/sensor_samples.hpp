#pragma once
/// @file sensor_samples.hpp Stamped proprioceptive measurements (encoders, IMU, GNSS).
#include <Eigen/Core>
#include <cstdint>

namespace rownav::core {

/// Cumulative wheel encoder counts. Differential / skid-steer robots use left / right;
/// car-like robots use left / right rear wheels plus the measured steering angle.
struct WheelEncoderSample {
  double stamp = 0.0;              ///< [s]
  std::int64_t left_ticks = 0;     ///< cumulative ticks, left wheel / track
  std::int64_t right_ticks = 0;    ///< cumulative ticks, right wheel / track
  double steering_angle = 0.0;     ///< [rad] car-like only (front wheel, bicycle model)
};

/// Body-frame inertial sample.
struct ImuSample {
  double stamp = 0.0;                                  ///< [s]
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();     ///< [rad/s]
  Eigen::Vector3d linear_acceleration = Eigen::Vector3d::Zero();  ///< [m/s^2] specific force
};

/// A GNSS fix already expressed in the local east-north-up frame of the field.
struct GnssFix {
  double stamp = 0.0;                                ///< [s]
  bool valid = false;                                ///< false during an outage
  Eigen::Vector3d position_enu = Eigen::Vector3d::Zero();  ///< [m]
  double horizontal_std = 0.0;                       ///< [m] 1-sigma
};

}  // namespace rownav::core
