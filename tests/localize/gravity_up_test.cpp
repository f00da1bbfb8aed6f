// localize::gravity_up: the base frame's up direction from the accelerometer.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rownav/localize/gravity_up.hpp"

namespace rownav::localize {
namespace {

core::ImuSample sample(double t, const Eigen::Vector3d& f, double gz = 0.0) {
  core::ImuSample s;
  s.stamp = t;
  s.linear_acceleration = f;
  s.angular_velocity = Eigen::Vector3d(0.0, 0.0, gz);
  return s;
}

TEST(GravityUp, RollFromTheAccelerometerWithTheCentripetalTermRemoved) {
  const double roll = 0.05, g = 9.80665, v = 1.0, omega = 0.2;
  const Eigen::Vector3d up(0.0, std::sin(roll), std::cos(roll));
  std::vector<core::ImuSample> imu;
  for (int i = 0; i < 20; ++i)  // turning left at v: v omega to the left on top of gravity
    imu.push_back(sample(0.01 * i, g * up + Eigen::Vector3d(0.0, v * omega, 0.0), omega));
  const auto u = gravity_up(imu, 0.05, 0.15, v);
  ASSERT_TRUE(u.has_value());
  EXPECT_NEAR(std::asin(u->y()), roll, 1e-9);
  const auto raw = gravity_up(imu, 0.05, 0.15, 0.0);  // without the speed: tilted by v omega / g
  ASSERT_TRUE(raw.has_value());
  EXPECT_GT(std::asin(raw->y()) - roll, 0.015);
}

TEST(GravityUp, NoSampleOrImplausibleForceGivesNothing) {
  std::vector<core::ImuSample> imu{sample(0.0, {0.0, 0.0, 9.8}), sample(0.1, {0.0, 0.0, 3.0})};
  EXPECT_FALSE(gravity_up(imu, 0.2, 0.3).has_value());
  EXPECT_FALSE(gravity_up(imu, 0.05, 0.15).has_value());  // 3 m/s^2: not gravity
  imu[0].linear_acceleration.x() = std::nan("");
  EXPECT_FALSE(gravity_up(imu, 0.0, 0.0).has_value());
}

}  // namespace
}  // namespace rownav::localize
