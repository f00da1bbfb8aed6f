#include "rownav/localize/pose_ekf.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rownav/core/angle.hpp"
#include "rownav/localize/wheel_odometry.hpp"

namespace rownav::localize {
namespace {

// Constant turn at 1 m/s, 0.3 rad/s: odometry twists at 50 Hz, gyro at 100 Hz (no noise).
// The constant-turn model (Lan 2021 eq. (9)-(14)) integrates the arc exactly.
TEST(PoseEkf, ConstantTurnRecovered) {
  for (const auto model : {MotionModel::constant_turn, MotionModel::constant_velocity}) {
    PoseEkfConfig c;
    c.motion_model = model;
    PoseEkf ekf(c);
    const core::Twist2 twist{1.0, 0.0, 0.3};
    ekf.reset(0.0);
    ekf.update_odometry(0.0, twist, false);  // already moving at t = 0
    for (int i = 1; i <= 1000; ++i) {
      const double t = i * 0.01;
      ekf.update_gyro(t, twist.omega);
      if (i % 2 == 0) ekf.update_odometry(t, twist, false);
    }
    const core::Pose2 truth = twist_increment(twist, 10.0);
    const core::Pose2 p = ekf.pose();
    // Observed: CT < 1 cm; CV (first order at 100 Hz) a few cm.
    const double tol = model == MotionModel::constant_turn ? 0.02 : 0.1;
    EXPECT_NEAR(p.x, truth.x, tol) << core::enum_name(model);
    EXPECT_NEAR(p.y, truth.y, tol) << core::enum_name(model);
    EXPECT_NEAR(core::angle_diff(p.theta, truth.theta), 0.0, 0.01);
    EXPECT_NEAR(ekf.twist().omega, 0.3, 1e-3);
  }
}

/// Heading error after 60 s of straight driving with a biased gyro and slipping odometry
/// (the robot stands still for the first 3 s); `bias_std` is the filter's bias prior.
double straight_drive_heading_error(double bias_prior_std, double* bias_estimate) {
  PoseEkfConfig c;
  c.initial_gyro_bias_std = bias_prior_std;
  PoseEkf ekf(c);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  const double bias = 0.005;  // [rad/s] one sigma of the simulated turn-on bias
  double slip = 0.0;          // correlated odometry yaw-rate error (0.5 s time constant)
  ekf.reset(0.0);
  for (int i = 1; i <= 6000; ++i) {
    const double t = i * 0.01;
    const bool moving = t > 3.0;
    ekf.update_gyro(t, bias + 0.003 * n(rng));
    if (i % 2 != 0) continue;
    slip = 0.96 * slip + 0.03 * std::sqrt(1.0 - 0.96 * 0.96) * n(rng);
    const core::Twist2 odo{moving ? 1.0 : 0.0, 0.0, moving ? slip : 0.0};
    ekf.update_odometry(t, odo, !moving);
  }
  if (bias_estimate) *bias_estimate = ekf.gyro_bias();
  return std::abs(ekf.pose().theta);  // true heading stays 0
}

TEST(PoseEkf, GyroBiasEstimationReducesHeadingDrift) {
  double bias = 0.0;
  const double with_bias = straight_drive_heading_error(0.01, &bias);
  const double without = straight_drive_heading_error(1e-9, nullptr);
  RecordProperty("heading_error_with_bias_state", std::to_string(with_bias));
  RecordProperty("heading_error_without", std::to_string(without));
  EXPECT_NEAR(bias, 0.005, 0.001);
  EXPECT_LT(with_bias, 0.3 * without);
  EXPECT_LT(with_bias, 0.02);
}

TEST(PoseEkf, TimeBackwardsIgnoredAndCounted) {
  PoseEkf ekf;
  ekf.reset(1.0);
  EXPECT_TRUE(ekf.update_odometry(1.1, {1.0, 0.0, 0.0}, false));
  EXPECT_FALSE(ekf.update_odometry(0.9, {5.0, 0.0, 0.0}, false));
  // Slightly late (interleaved streams): applied at the filter time.
  EXPECT_TRUE(ekf.update_gyro(1.09, 0.0));
  EXPECT_FALSE(ekf.update_gyro(0.5, 1.0));
  EXPECT_EQ(ekf.rejected_time(), 2);
  EXPECT_DOUBLE_EQ(ekf.stamp(), 1.1);
  EXPECT_FALSE(ekf.update_gyro(1.2, std::nan("")));
  EXPECT_EQ(ekf.rejected_outliers(), 1);
  EXPECT_TRUE(ekf.state().allFinite());
}

TEST(PoseEkf, PositionOutlierGatedInlierPulls) {
  PoseEkf ekf;
  ekf.reset(0.0);
  for (int i = 1; i <= 50; ++i) ekf.update_odometry(i * 0.02, {1.0, 0.0, 0.0}, false);
  const core::Pose2 before = ekf.pose();
  EXPECT_FALSE(ekf.update_position(1.0, {before.x + 50.0, before.y}, 0.05));  // multipath jump
  EXPECT_EQ(ekf.rejected_outliers(), 1);
  EXPECT_TRUE(ekf.update_position(1.0, {before.x + 0.05, before.y + 0.05}, 0.05));
  EXPECT_GT(ekf.pose().y, before.y + 1e-4);  // pulled towards the fix, not onto it
  EXPECT_LT(ekf.pose().y, before.y + 0.05);
}

}  // namespace
}  // namespace rownav::localize
