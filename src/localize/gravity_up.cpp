#include "rownav/localize/gravity_up.hpp"

#include <algorithm>
#include <cmath>

namespace rownav::localize {

std::optional<Eigen::Vector3d> gravity_up(std::span<const core::ImuSample> imu, double t0,
                                          double t1, double forward_speed) {
  constexpr double kGravity = 9.80665;  // [m/s^2] standard gravity
  const auto first = std::lower_bound(
      imu.begin(), imu.end(), t0, [](const core::ImuSample& s, double t) { return s.stamp < t; });
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  double omega = 0.0;
  int n = 0;
  for (auto it = first; it != imu.end() && it->stamp <= t1; ++it, ++n) {
    if (!it->linear_acceleration.allFinite() || !std::isfinite(it->angular_velocity.z()))
      return std::nullopt;
    f += it->linear_acceleration;
    omega += it->angular_velocity.z();
  }
  if (n == 0 || !std::isfinite(forward_speed)) return std::nullopt;
  f /= n;
  // Body acceleration of a planar motion at constant speed: v omega to the left (+y).
  f.y() -= forward_speed * omega / n;
  const double norm = f.norm();
  if (std::abs(norm - kGravity) > 0.2 * kGravity) return std::nullopt;
  return Eigen::Vector3d(f / norm);
}

}  // namespace rownav::localize
