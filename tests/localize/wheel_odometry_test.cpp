#include "rownav/localize/wheel_odometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "rownav/core/angle.hpp"

namespace rownav::localize {
namespace {

/// Encoder stream of a robot driven with constant wheel ground speeds [m/s] and steering angle for
/// `seconds` at 50 Hz, ticks quantised as the simulator does (floor of the cumulative angle).
std::vector<core::WheelEncoderSample> tick_stream(const WheelOdometryConfig& c, double vl,
                                                  double vr, double steering, double seconds) {
  std::vector<core::WheelEncoderSample> out;
  const double dt = 0.02;
  const int n = static_cast<int>(std::lround(seconds / dt));
  auto ticks = [&](double distance) {
    return static_cast<std::int64_t>(
        std::floor(distance / c.wheel_radius / (2.0 * std::numbers::pi) * c.ticks_per_rev));
  };
  for (int i = 0; i <= n; ++i) {
    const double t = i * dt;
    out.push_back({t, ticks(vl * t), ticks(vr * t), steering});
  }
  return out;
}

/// Exact pose after `seconds` of a constant twist from the origin.
core::Pose2 arc(const core::Twist2& t, double seconds) {
  return twist_increment(t, seconds);
}

core::Pose2 run(WheelOdometry& odo, const std::vector<core::WheelEncoderSample>& stream) {
  for (const auto& s : stream) odo.add(s);
  return odo.pose();
}

// One tick is 2 pi 0.165 / 2048 = 0.5 mm of wheel travel: the cumulative counts keep the pose
// within a few ticks of the true arc.
constexpr double kPosTol = 0.005;   // [m]
constexpr double kHeadTol = 0.005;  // [rad]

void expect_near(const core::Pose2& a, const core::Pose2& b) {
  EXPECT_NEAR(a.x, b.x, kPosTol);
  EXPECT_NEAR(a.y, b.y, kPosTol);
  EXPECT_NEAR(core::angle_diff(a.theta, b.theta), 0.0, kHeadTol);
}

TEST(WheelOdometry, DifferentialArcExact) {
  WheelOdometryConfig c;
  c.model = DriveModel::differential;
  WheelOdometry odo(c);
  const double vl = 0.8, vr = 1.0;
  const core::Pose2 p = run(odo, tick_stream(c, vl, vr, 0.0, 10.0));
  const core::Twist2 truth{0.9, 0.0, (vr - vl) / c.track_width};
  expect_near(p, arc(truth, 10.0));
  EXPECT_GT(std::abs(p.y), 1.0);  // a real arc, not a straight line
}

TEST(WheelOdometry, SkidSteerArcExactWithCalibratedIcr) {
  WheelOdometryConfig c;
  c.model = DriveModel::skid_steer;
  c.x_icr = 0.40;  // "true" calibrated values of Bertoglio 2023 eq. (2)
  c.alpha = 0.9;
  WheelOdometry odo(c);
  const double vl = 0.6, vr = 1.0;
  const core::Pose2 p = run(odo, tick_stream(c, vl, vr, 0.0, 10.0));
  // Bertoglio 2023 eq. (1)-(2) written out independently.
  const core::Twist2 truth{0.9 * 0.5 * (vl + vr), 0.0, 0.9 / 0.8 * (vr - vl)};
  expect_near(p, arc(truth, 10.0));
  // The nominal model on the same ticks turns much more (x_icr = 0.275 < 0.40).
  WheelOdometry nominal(WheelOdometryConfig{});
  const core::Pose2 q = run(nominal, tick_stream(c, vl, vr, 0.0, 10.0));
  EXPECT_GT(std::abs(core::angle_diff(q.theta, p.theta)), 0.5);
}

TEST(WheelOdometry, AckermannBicycleArcExact) {
  WheelOdometryConfig c;
  c.model = DriveModel::ackermann;
  WheelOdometry odo(c);
  const double delta = 0.3, v = 1.0;
  const double w = v * std::tan(delta) / c.wheelbase;
  const double half = 0.5 * c.track_width;
  const core::Pose2 p = run(odo, tick_stream(c, v - w * half, v + w * half, delta, 8.0));
  expect_near(p, arc({v, 0.0, w}, 8.0));
}

TEST(WheelOdometry, FirstSampleAndTimeBackwardsGiveNoTwist) {
  WheelOdometry odo;
  EXPECT_FALSE(odo.add({1.0, 0, 0, 0.0}));
  const auto t = odo.add({1.02, 100, 100, 0.0});
  ASSERT_TRUE(t);
  EXPECT_GT(t->v, 0.0);
  EXPECT_FALSE(odo.add({1.02, 150, 150, 0.0}));  // equal stamp
  EXPECT_FALSE(odo.add({1.00, 150, 150, 0.0}));  // backwards
  EXPECT_EQ(odo.rejected_time(), 2);
  EXPECT_TRUE(odo.add({1.04, 200, 200, 0.0}));
}

TEST(WheelOdometry, TickJumpRejectedAndReanchored) {
  WheelOdometryConfig c;
  c.model = DriveModel::differential;
  WheelOdometry odo(c);
  odo.add({0.0, 0, 0, 0.0});
  odo.add({0.02, 40, 40, 0.0});
  const double x_before = odo.pose().x;
  // A glitch of a million ticks (500 m in 20 ms): not integrated, counted.
  EXPECT_FALSE(odo.add({0.04, 1000040, 80, 0.0}));
  EXPECT_EQ(odo.rejected_jumps(), 1);
  EXPECT_DOUBLE_EQ(odo.pose().x, x_before);
  // Counting continues from the glitched value: the next interval is normal again.
  const auto t = odo.add({0.06, 1000080, 120, 0.0});
  ASSERT_TRUE(t);
  EXPECT_NEAR(t->omega, 0.0, 1e-9);
  EXPECT_GT(odo.pose().x, x_before);
}

TEST(WheelOdometry, NonFiniteStampDropped) {
  WheelOdometry odo;
  odo.add({0.0, 0, 0, 0.0});
  EXPECT_FALSE(odo.add({std::nan(""), 10, 10, 0.0}));
  EXPECT_TRUE(std::isfinite(odo.pose().x));
}

TEST(WheelOdometryConfig, ValidateNamesField) {
  WheelOdometryConfig c;
  c.x_icr = 0.0;
  try {
    c.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("x_icr"), std::string::npos);
  }
}

}  // namespace
}  // namespace rownav::localize
