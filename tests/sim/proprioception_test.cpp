#include "rownav/sim/proprioception.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace rownav::sim {
namespace {

struct Stats {
  double mean = 0.0, std = 0.0;
};
Stats stats(const std::vector<double>& x) {
  Stats s;
  for (double v : x) s.mean += v;
  s.mean /= static_cast<double>(x.size());
  for (double v : x) s.std += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(s.std / static_cast<double>(x.size() - 1));
  return s;
}

TEST(WheelEncoders, QuantiseCumulativeAngle) {
  WheelEncoders enc(EncoderConfig{}, 1);
  RobotState st;
  st.left_wheel_angle = 2.0 * std::numbers::pi * 1.5;
  st.right_wheel_angle = -1e-4;
  const auto s = enc.sample(st);
  EXPECT_EQ(s.left_ticks, 3072);
  EXPECT_EQ(s.right_ticks, -1);  // floor, not truncation
  st.left_wheel_angle = 2.0 * std::numbers::pi / 2048 * 0.999;
  EXPECT_EQ(enc.sample(st).left_ticks, 0);
}

TEST(WheelEncoders, TicksMatchDistanceDriven) {
  RobotConfig c;
  c.x_icr = 0.5 * c.track_width;
  c.alpha = 1.0;
  c.slip_noise = 0.0;
  Robot r(c, 1, core::Pose2());
  WheelEncoders enc(EncoderConfig{}, 1);
  for (int i = 0; i < 1000; ++i) r.step({1.0, 0.0, 0.0}, 0.01);
  const auto s = enc.sample(r.state());
  const double per_tick = 2.0 * std::numbers::pi * c.wheel_radius / 2048;
  EXPECT_NEAR(s.left_ticks * per_tick, r.state().pose.x, per_tick);
  EXPECT_NEAR(s.right_ticks * per_tick, r.state().pose.x, per_tick);
  EXPECT_EQ(s.stamp, r.state().stamp);
}

TEST(Imu, GyroBiasAndWhiteNoiseStatistics) {
  ImuConfig c;
  c.gyro_bias_random_walk = 0.0;
  Imu imu(c, 5);
  RobotState st;
  std::vector<double> gz, az;
  for (int i = 0; i < 20000; ++i) {
    st.stamp = i * 0.01;
    const auto s = imu.sample(st, 0.0, 0.0);
    gz.push_back(s.angular_velocity.z());
    az.push_back(s.linear_acceleration.z());
  }
  const Stats g = stats(gz), a = stats(az);
  const double sigma = c.gyro_noise_density * std::sqrt(c.rate_hz);  // 2e-3 rad/s
  EXPECT_NEAR(g.std, sigma, 0.05 * sigma);
  EXPECT_NEAR(g.mean, imu.gyro_bias().z(), 4.0 * sigma / std::sqrt(20000.0));
  EXPECT_GT(std::abs(imu.gyro_bias().z()), 1e-5);  // a turn-on bias exists
  EXPECT_LT(std::abs(imu.gyro_bias().z()), 5.0 * c.gyro_bias_std);
  EXPECT_NEAR(a.mean, 9.80665, 5.0 * c.accel_bias_std);
  EXPECT_NEAR(a.std, c.accel_noise_density * std::sqrt(c.rate_hz), 0.002);
}

TEST(Imu, BiasRandomWalkGrowsWithSqrtTime) {
  ImuConfig c;
  c.gyro_bias_std = 0.0;
  c.gyro_bias_random_walk = 1e-3;
  std::vector<double> drift;
  for (std::uint64_t seed = 0; seed < 400; ++seed) {
    Imu imu(c, seed);
    RobotState st;
    for (int i = 0; i <= 1000; ++i) {  // 10 s
      st.stamp = i * 0.01;
      imu.sample(st, 0.0, 0.0);
    }
    drift.push_back(imu.gyro_bias().z());
  }
  EXPECT_NEAR(stats(drift).std, 1e-3 * std::sqrt(10.0), 0.1 * 1e-3 * std::sqrt(10.0));
}

TEST(Imu, GravityProjectionAndCentripetalAcceleration) {
  ImuConfig c;
  c.gyro_noise_density = c.accel_noise_density = c.gyro_bias_std = c.accel_bias_std = 0.0;
  c.gyro_bias_random_walk = 0.0;
  Imu imu(c, 1);
  RobotState st;
  st.twist = {1.0, 0.0, 0.5};
  imu.sample(st, 0.1, -0.2);
  st.stamp = 0.01;
  const auto s = imu.sample(st, 0.1, -0.2);
  const double g = 9.80665;
  EXPECT_NEAR(s.linear_acceleration.x(), g * std::sin(0.2), 1e-9);  // nose up: +x
  EXPECT_NEAR(s.linear_acceleration.y(), 0.5 + g * std::sin(0.1) * std::cos(0.2), 1e-9);
  EXPECT_NEAR(s.linear_acceleration.z(), g * std::cos(0.1) * std::cos(0.2), 1e-9);
  EXPECT_NEAR(s.angular_velocity.z(), 0.5 * std::cos(0.1) * std::cos(0.2), 1e-9);
}

TEST(Gnss, OutagesOnlyInLanesAndCanopyNoise) {
  GnssConfig c;
  c.enabled = true;
  c.outage_probability_in_lane = 0.05;
  Gnss gnss(c, 9);
  int lane_invalid = 0, other_invalid = 0;
  std::vector<double> open_err, lane_err;
  for (int i = 0; i < 20000; ++i) {
    const double t = i * 0.2;
    // 60 s in a lane, then 20 s in the headland, repeatedly.
    const Place place = std::fmod(t, 80.0) < 60.0 ? Place::lane : Place::headland;
    const Eigen::Vector3d truth(t, 1.0, 0.0);
    const auto f = gnss.sample(t, truth, place);
    if (!f.valid) (place == Place::lane ? lane_invalid : other_invalid)++;
    if (f.valid) (place == Place::lane ? lane_err : open_err).push_back(f.position_enu.x() - t);
  }
  EXPECT_EQ(other_invalid, 0);
  // Expected share of lane time in outage: r*d / (1 + r*d) = 0.2, less the cut-offs at lane exits.
  const double share = lane_invalid / 15000.0;
  EXPECT_GT(share, 0.08);
  EXPECT_LT(share, 0.3);
  EXPECT_NEAR(stats(open_err).std, c.noise_std, 0.1 * c.noise_std);
  EXPECT_NEAR(stats(lane_err).std, c.noise_std * c.canopy_noise_factor,
              0.1 * c.noise_std * c.canopy_noise_factor);
}

TEST(Gnss, DisabledGivesNoFix) {
  Gnss gnss(GnssConfig{}, 1);
  for (int i = 0; i < 10; ++i)
    EXPECT_FALSE(gnss.sample(i * 0.2, Eigen::Vector3d::Zero(), Place::headland).valid);
}

}  // namespace
}  // namespace rownav::sim
