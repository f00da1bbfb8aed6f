#include "rownav/control/velocity_limits.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "rownav/control/front_obstacle.hpp"

namespace rownav::control {
namespace {

TEST(VelocityLimits, ClampsSpeedAndYawRate) {
  const VelocityLimits lim;
  const auto t = apply_limits({5.0, 0.3, -9.0}, {lim.max_speed, 0.0, -lim.max_yaw_rate}, 0.1, lim);
  EXPECT_DOUBLE_EQ(t.v, lim.max_speed);
  EXPECT_DOUBLE_EQ(t.omega, -lim.max_yaw_rate);
  EXPECT_EQ(t.vy, 0.0);
  const auto r = apply_limits({-5.0, 0.0, 0.0}, {-lim.max_reverse_speed, 0.0, 0.0}, 0.1, lim);
  EXPECT_DOUBLE_EQ(r.v, -lim.max_reverse_speed);
}

TEST(VelocityLimits, AccelerationLimitsTheStep) {
  const VelocityLimits lim;
  const auto t = apply_limits({1.0, 0.0, 1.0}, {}, 0.1, lim);
  EXPECT_NEAR(t.v, lim.max_accel * 0.1, 1e-12);
  EXPECT_NEAR(t.omega, lim.max_yaw_accel * 0.1, 1e-12);
  // dt <= 0 or NaN: no acceleration limit (no time base), the plain clamps still hold.
  EXPECT_DOUBLE_EQ(apply_limits({0.7, 0.0, 0.0}, {}, 0.0, lim).v, 0.7);
  EXPECT_DOUBLE_EQ(apply_limits({0.7, 0.0, 0.0}, {}, std::nan(""), lim).v, 0.7);
}

TEST(VelocityLimits, CurvatureLimitForCarLikeRobots) {
  VelocityLimits lim;
  lim.min_turn_radius = 2.0;
  const auto t = apply_limits({0.5, 0.0, 1.0}, {0.5, 0.0, 1.0}, 0.1, lim);
  EXPECT_NEAR(t.omega, 0.25, 1e-12);  // |omega| <= |v| / R
  EXPECT_EQ(apply_limits({0.0, 0.0, 0.5}, {0.0, 0.0, 0.5}, 0.1, lim).omega, 0.0);
  lim.min_turn_radius = 0.0;  // turns in place
  EXPECT_DOUBLE_EQ(apply_limits({0.0, 0.0, 0.5}, {0.0, 0.0, 0.5}, 0.1, lim).omega, 0.5);
}

TEST(VelocityLimits, NanBecomesZero) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto t = apply_limits({nan, 0.0, nan}, {nan, 0.0, nan}, 0.1, VelocityLimits{});
  EXPECT_EQ(t.v, 0.0);
  EXPECT_EQ(t.omega, 0.0);
}

TEST(VelocityLimits, ValidateNamesTheField) {
  VelocityLimits lim;
  lim.max_accel = -1.0;
  try {
    lim.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_accel"), std::string::npos);
  }
}

TEST(FrontObstacle, NearestPointInsideTheRectangle) {
  const FrontRectConfig cfg;  // |y| <= 0.5, x in [0.5, 3.5]
  const std::vector<Eigen::Vector2f> pts = {{2.0f, 0.0f},          {1.5f, 0.45f},
                                            {1.0f, 0.8f},  // the last one is beside the rectangle
                                            {0.2f, 0.0f},  // behind the front
                                            {std::nanf(""), 0.0f}, {9.0f, 0.0f}};  // NaN, too far
  EXPECT_NEAR(front_obstacle_distance(pts, cfg), 1.0, 1e-6);
  EXPECT_TRUE(std::isinf(front_obstacle_distance({}, cfg)));
}

TEST(FrontObstacle, SpeedFallsLinearlyToStop) {
  const SlowdownConfig cfg;
  EXPECT_DOUBLE_EQ(obstacle_limited_speed(1.0, std::numeric_limits<double>::infinity(), cfg), 1.0);
  const double mid = 0.5 * (cfg.slow_down_distance + cfg.stop_distance);
  EXPECT_NEAR(obstacle_limited_speed(1.0, mid, cfg), 0.5, 1e-12);
  EXPECT_EQ(obstacle_limited_speed(1.0, cfg.stop_distance - 0.1, cfg), 0.0);
  EXPECT_EQ(obstacle_limited_speed(1.0, std::nan(""), cfg), 0.0);
}

}  // namespace
}  // namespace rownav::control
