#pragma once
/// @file twist.hpp Planar body velocities.

namespace rownav::core {

/// Body-frame velocity command or estimate: x forward, y left, yaw rate counter-clockwise.
struct Twist2 {
  double v = 0.0;      ///< [m/s] forward speed
  double vy = 0.0;     ///< [m/s] lateral speed (skid-steer side slip; 0 for ideal robots)
  double omega = 0.0;  ///< [rad/s] yaw rate
};

}  // namespace rownav::core
