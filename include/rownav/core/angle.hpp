#pragma once
/// @file angle.hpp Angle helpers: radians inside, degrees only at the edges (configs, reports).
#include <cmath>
#include <numbers>

namespace rownav::core {

/// Degrees to radians.
constexpr double deg2rad(double deg) { return deg * std::numbers::pi / 180.0; }
/// Radians to degrees.
constexpr double rad2deg(double rad) { return rad * 180.0 / std::numbers::pi; }

/// Wraps an angle to (-pi, pi].
inline double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  if (a <= -std::numbers::pi) a += 2.0 * std::numbers::pi;
  return a;
}

/// Signed smallest difference a - b, in (-pi, pi].
inline double angle_diff(double a, double b) { return wrap_angle(a - b); }

}  // namespace rownav::core
