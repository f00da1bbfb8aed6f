#include "rownav/localize/localizer.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "rownav/core/angle.hpp"

namespace rownav::localize {
namespace {

/// Cumulative ticks of a wheel that travelled `distance` [m] (default odometry geometry).
std::int64_t ticks(double distance) {
  const WheelOdometryConfig c;
  return static_cast<std::int64_t>(
      std::floor(distance / c.wheel_radius / (2.0 * M_PI) * c.ticks_per_rev));
}

/// Straight drive at `speed` from t0 for `seconds`: encoders at 50 Hz, IMU (zero rate) at 100 Hz.
void drive_straight(Localizer& loc, double t0, double seconds, double speed, double& distance,
                    bool imu = true) {
  const int n = static_cast<int>(std::lround(seconds / 0.01));
  for (int i = 1; i <= n; ++i) {
    const double t = t0 + i * 0.01;
    distance += speed * 0.01;
    if (imu) {
      core::ImuSample s;
      s.stamp = t;
      loc.add_imu(s);
    }
    if (i % 2 == 0) loc.add_encoders({t, ticks(distance), ticks(distance), 0.0});
  }
}

TEST(Localizer, OdometryOnlyWithoutImu) {
  Localizer loc;
  EXPECT_FALSE(loc.latest().valid);
  double d = 0.0;
  loc.add_encoders({0.0, 0, 0, 0.0});
  drive_straight(loc, 0.0, 5.0, 1.0, d, false);
  const PoseEstimate e = loc.latest();
  EXPECT_TRUE(e.valid);
  EXPECT_NEAR(e.T_odom_base.x, 5.0, 0.05);
  EXPECT_NEAR(e.T_odom_base.y, 0.0, 1e-6);
  EXPECT_NEAR(e.twist.v, 1.0, 0.01);
}

TEST(Localizer, BadInputNoCrashFiniteAndRecovers) {
  LocalizerConfig c;
  Localizer loc(c);
  double d = 0.0;
  loc.add_encoders({0.0, 0, 0, 0.0});
  drive_straight(loc, 0.0, 2.0, 1.0, d);
  // Time going backwards on every stream.
  loc.add_encoders({1.0, ticks(d), ticks(d), 0.0});
  core::ImuSample old;
  old.stamp = 0.5;
  old.angular_velocity.z() = 3.0;
  loc.add_imu(old);
  // NaN IMU sample, an encoder jump of 10^6 ticks on one wheel.
  core::ImuSample bad;
  bad.stamp = 2.005;
  bad.angular_velocity.z() = std::nan("");
  loc.add_imu(bad);
  loc.add_encoders({2.02, ticks(d) + 1000000, ticks(d), 0.0});
  // GNSS: invalid fixes (outage) and a NaN fix.
  core::GnssFix outage;
  outage.stamp = 2.02;
  loc.add_gnss(outage);
  core::GnssFix nan_fix;
  nan_fix.stamp = 2.02;
  nan_fix.valid = true;
  nan_fix.position_enu.x() = std::nan("");
  loc.add_gnss(nan_fix);
  const LocalizerStats st = loc.stats();
  EXPECT_EQ(st.encoder_time_rejected, 1);
  EXPECT_EQ(st.encoder_jumps, 1);
  EXPECT_GE(st.time_rejected, 1);
  EXPECT_GE(st.outliers, 2);
  EXPECT_EQ(st.gnss_invalid, 1);
  // Recovers: ticks keep counting from the glitched value; the pose keeps moving forward.
  const double x_before = loc.latest().T_odom_base.x;
  std::int64_t left = ticks(d) + 1000000;
  for (int i = 1; i <= 100; ++i) {
    const std::int64_t step = ticks(d + 0.02) - ticks(d);
    d += 0.02;
    left += step;
    loc.add_encoders({2.02 + i * 0.02, left, ticks(d), 0.0});
  }
  const PoseEstimate e = loc.latest();
  EXPECT_TRUE(e.T_odom_base.translation().allFinite());
  EXPECT_TRUE(e.covariance.allFinite());
  EXPECT_NEAR(e.T_odom_base.x - x_before, 2.0, 0.1);
  EXPECT_NEAR(e.T_odom_base.theta, 0.0, 0.01);
}

TEST(Localizer, GnssAlignedAfterTravelAndCorrectsDrift) {
  LocalizerConfig c;
  c.odometry.alpha = 1.1;  // the odometry over-reads the distance by 10 %
  Localizer loc(c);
  double d = 0.0;  // odometry distance; the true one is d / 1.1
  loc.add_encoders({0.0, 0, 0, 0.0});
  double x_mid = 0.0, d_mid = 0.0;
  // ENU frame rotated 90 deg from odom and offset: true position (100, 200) + (0, s).
  for (int k = 0; k < 100; ++k) {
    drive_straight(loc, k * 0.2, 0.2, 1.0, d);
    core::GnssFix f;
    f.stamp = (k + 1) * 0.2;
    f.valid = true;
    f.horizontal_std = 0.05;
    f.position_enu = Eigen::Vector3d(100.0, 200.0 + d / 1.1, 0.0);
    loc.add_gnss(f);
    if (k == 49) {
      x_mid = loc.latest().T_odom_base.x;
      d_mid = d;
    }
  }
  // Aligned after 5 m of travel (~28 fixes); from then on the estimate follows the true distance
  // (9.1 m over the last 50 fixes), not the odometry's 10 m.
  const double travelled = loc.latest().T_odom_base.x - x_mid;
  EXPECT_GT(loc.stats().gnss_used, 50);
  EXPECT_NEAR(travelled, (d - d_mid) / 1.1, 0.2);
  EXPECT_NEAR(loc.latest().T_odom_base.y, 0.0, 0.05);
}

TEST(Localizer, InterpolationExactBetweenSamples) {
  Localizer loc;
  double d = 0.0;
  loc.add_encoders({0.0, 0, 0, 0.0});
  drive_straight(loc, 0.0, 1.0, 1.0, d);
  // Estimates are stored at every IMU stamp (10 ms).
  const auto a = loc.estimate_at(0.50);
  const auto b = loc.estimate_at(0.51);
  ASSERT_TRUE(a && b);
  EXPECT_GT(b->T_odom_base.x, a->T_odom_base.x + 0.005);
  const auto m = loc.T_odom_base(0.505);
  ASSERT_TRUE(m);
  const core::Pose2 expected = core::interpolate(a->T_odom_base, b->T_odom_base, 0.5);
  EXPECT_NEAR(m->x, expected.x, 1e-9);
  EXPECT_NEAR(m->y, expected.y, 1e-9);
  EXPECT_NEAR(m->theta, expected.theta, 1e-9);
  // Stored stamps are returned exactly; a quarter of the way is a quarter of the motion.
  const auto q = loc.T_odom_base(0.5025);
  ASSERT_TRUE(q);
  EXPECT_NEAR(q->x, a->T_odom_base.x + 0.25 * (b->T_odom_base.x - a->T_odom_base.x), 1e-9);
  // Extrapolation by the last twist up to max_extrapolation, nothing beyond or before.
  const PoseEstimate last = loc.latest();
  const auto ex = loc.T_odom_base(last.stamp + 0.1);
  ASSERT_TRUE(ex);
  EXPECT_NEAR(ex->x, last.T_odom_base.x + 0.1 * last.twist.v, 1e-9);
  EXPECT_FALSE(loc.T_odom_base(last.stamp + 0.5));
  EXPECT_FALSE(loc.T_odom_base(-1.0));
}

TEST(Localizer, HistoryBounded) {
  LocalizerConfig c;
  c.history = 1.0;
  Localizer loc(c);
  double d = 0.0;
  loc.add_encoders({0.0, 0, 0, 0.0});
  drive_straight(loc, 0.0, 5.0, 1.0, d);
  EXPECT_FALSE(loc.T_odom_base(3.5));
  EXPECT_TRUE(loc.T_odom_base(4.5));
}

TEST(Localizer, ResetRestartsAtPose) {
  Localizer loc;
  double d = 0.0;
  loc.add_encoders({0.0, 0, 0, 0.0});
  drive_straight(loc, 0.0, 1.0, 1.0, d);
  loc.reset({1.0, 2.0, 0.5});
  EXPECT_NEAR(loc.latest().T_odom_base.y, 2.0, 1e-9);
  drive_straight(loc, 1.0, 1.0, 1.0, d);
  const core::Pose2 p = loc.latest().T_odom_base;
  EXPECT_NEAR(p.x, 1.0 + std::cos(0.5), 0.05);
  EXPECT_NEAR(p.y, 2.0 + std::sin(0.5), 0.05);
}

TEST(LocalizerConfig, ValidateNamesNestedField) {
  LocalizerConfig c;
  c.ekf.gyro_std = -1.0;
  try {
    c.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ekf.gyro_std"), std::string::npos);
  }
}

}  // namespace
}  // namespace rownav::localize
