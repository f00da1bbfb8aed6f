// Closed-loop convergence of every path controller on a kinematic unicycle (closed_loop.hpp):
// from 0.3 m and 10 deg off the path, on a straight and a gently curved (R = 30 m) path.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>

#include "control/closed_loop.hpp"
#include "rownav/control/fir_pid.hpp"
#include "rownav/control/lookahead_pid.hpp"
#include "rownav/control/pure_pursuit.hpp"
#include "rownav/control/stanley.hpp"

namespace rownav::control {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::unique_ptr<PathController> make(const std::string& name) {
  if (name == "stanley") return std::make_unique<StanleyController>();
  if (name == "lookahead_pid") return std::make_unique<LookaheadPidController>();
  if (name == "fir_pid") return std::make_unique<FirPidController>();
  return std::make_unique<PurePursuitController>();
}

class ControllerConvergence : public ::testing::TestWithParam<std::string> {};

// Requirements shared by every controller: converge within 20 s (10 m at 0.5 m/s), cross the path
// by less than 5 cm, command less than 1.5 rad/s.
void expect_converges(const test::ClosedLoopResult& r, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_LT(r.final_abs_lateral, 0.02);
  EXPECT_GE(r.settle_time, 0.0);
  EXPECT_LT(r.settle_time, 20.0);
  EXPECT_LT(r.overshoot, 0.05);
  EXPECT_LT(r.max_abs_omega, 1.5);
  std::printf("[ %-13s ] %-28s settle %.1f s, overshoot %.3f m, max |omega| %.2f rad/s\n",
              what.substr(0, what.find(' ')).c_str(), what.c_str() + what.find(' ') + 1,
              r.settle_time, r.overshoot, r.max_abs_omega);
}

TEST_P(ControllerConvergence, StraightPathFromOffsetAndHeading) {
  for (const double sign : {1.0, -1.0}) {
    auto c = make(GetParam());
    const auto r = test::run_closed_loop(*c, 0.0, sign * 0.3, sign * 10.0 * kDeg, 30.0);
    expect_converges(r, GetParam() + " straight " + (sign > 0 ? "left" : "right"));
  }
}

TEST_P(ControllerConvergence, StraightPathHeadingAwayFromPath) {
  // Offset left, heading further left: the controller must first turn back.
  auto c = make(GetParam());
  const auto r = test::run_closed_loop(*c, 0.0, 0.3, -10.0 * kDeg, 30.0);
  expect_converges(r, GetParam() + " straight towards");
}

TEST_P(ControllerConvergence, GentlyCurvedPath) {
  for (const double radius : {30.0}) {
    auto c = make(GetParam());
    const auto r = test::run_closed_loop(*c, radius, 0.3, 10.0 * kDeg, 30.0);
    expect_converges(r, GetParam() + " curved R=" + std::to_string(int(radius)));
  }
}

TEST_P(ControllerConvergence, FasterSpeedStillConverges) {
  auto c = make(GetParam());
  const auto r = test::run_closed_loop(*c, 0.0, 0.3, 10.0 * kDeg, 30.0, 1.0);
  expect_converges(r, GetParam() + " straight 1 m/s");
}

TEST_P(ControllerConvergence, ObstacleSlowsDownThenStops) {
  auto c = make(GetParam());
  ControlInput in;
  in.speed_ref = 0.8;
  const double clear = c->compute(in).v;
  EXPECT_DOUBLE_EQ(clear, 0.8);
  in.obstacle_distance = 1.0;
  const double slowed = c->compute(in).v;
  EXPECT_GT(slowed, 0.0);
  EXPECT_LT(slowed, clear);
  in.obstacle_distance = 0.3;  // below the default stop distance
  EXPECT_DOUBLE_EQ(c->compute(in).v, 0.0);
}

TEST_P(ControllerConvergence, NonFiniteInputStops) {
  auto c = make(GetParam());
  ControlInput in;
  in.lateral_error = std::numeric_limits<double>::quiet_NaN();
  const auto t = c->compute(in);
  EXPECT_EQ(t.v, 0.0);
  EXPECT_EQ(t.omega, 0.0);
  in.lateral_error = 0.1;  // the next valid frame is handled normally
  in.path_base.point = Eigen::Vector2d(0.0, -0.1);
  EXPECT_LT(c->compute(in).omega, 0.0);
}

INSTANTIATE_TEST_SUITE_P(All, ControllerConvergence,
                         ::testing::Values("stanley", "lookahead_pid", "fir_pid", "pure_pursuit"));

TEST(Stanley, ErrorDecaysAtRateK) {
  // Lan 2021 eq. (20)-(21): e(t) ~ e(0) exp(-k t) for small errors once the heading follows.
  StanleyConfig cfg;
  cfg.yaw_gain = 20.0;  // heading follows delta almost instantly: the eq. (20) regime
  StanleyController c(cfg);
  VelocityLimits fast;  // no actuator lag either
  fast.max_yaw_accel = 1000.0;
  fast.max_yaw_rate = 10.0;
  const auto r = test::run_closed_loop(c, 0.0, 0.05, 0.0, 2.0, 0.5, 0.01, fast);
  // After 2 s at k = 1: 0.05 exp(-2) = 6.8 mm; allow the heading lag.
  EXPECT_LT(r.final_abs_lateral, 0.05 * std::exp(-2.0 * cfg.k) * 1.5);
  EXPECT_GT(r.final_abs_lateral, 0.05 * std::exp(-2.0 * cfg.k) * 0.5);
}

// Issue 11 (Bertoglio 2023 at 2 m/s): the heading loop of a robot that turns in place closes in
// the same distance at any speed above 0.8 m/s, as the bicycle model's v tan(delta) / L does;
// up to 0.8 m/s it is yaw_gain delta as before.
TEST(Stanley, AboveTheRowSpeedTheYawGainGrowsWithSpeed) {
  StanleyConfig cfg;  // yaw_gain 2 /s, yaw_gain_per_speed 2.5 /m
  ControlInput in;
  in.heading_error = 0.1;  // delta = -0.1 rad with e = 0
  auto omega_at = [&](const StanleyConfig& c, double v) {
    in.speed_ref = v;
    in.speed = v;
    return StanleyController(c).compute(in).omega;
  };
  EXPECT_DOUBLE_EQ(omega_at(cfg, 0.4), -0.2);
  EXPECT_DOUBLE_EQ(omega_at(cfg, 0.8), -0.2);
  EXPECT_NEAR(omega_at(cfg, 2.0), -0.5, 1e-12);  // 2.5 /m x 2 m/s
  StanleyConfig fixed = cfg;
  fixed.yaw_gain_per_speed = 0.0;
  EXPECT_DOUBLE_EQ(omega_at(fixed, 2.0), -0.2);
  fixed.yaw_gain_per_speed = -1.0;
  EXPECT_THROW(StanleyController{fixed}, std::invalid_argument);
}

TEST(FirPid, SteepModelsCorrectACentredTurnedRobot) {
  // Malavazi 2018 Fig. 7: centred between two steep models the plain error is 0; the safety
  // gives a correction towards the path direction, slows down and bounds omega.
  FirPidController c;
  ControlInput in;
  in.heading_error = 30.0 * kDeg;
  in.steepness = std::tan(30.0 * kDeg);
  const auto t = c.compute(in);
  EXPECT_LT(t.omega, 0.0);
  EXPECT_GE(t.omega, -c.config().steep_max_omega);
  EXPECT_DOUBLE_EQ(t.v, in.speed_ref * c.config().steep_speed_scale);
  FirPidController flat;
  in.steepness = 0.0;
  EXPECT_EQ(flat.compute(in).omega, 0.0);
}

TEST(FirPid, FirCoefficientsAreNormalised) {
  FirPidConfig cfg;
  cfg.fir = {2.0, 2.0};
  cfg.pid = {1.0, 0.0, 0.0, 0.5};
  FirPidController c(cfg);
  ControlInput in;
  in.lateral_error = 0.2;
  EXPECT_NEAR(c.compute(in).omega, -0.2, 1e-12);  // constant error: unit DC gain
  cfg.fir = {1.0, -1.0};
  EXPECT_THROW(FirPidController{cfg}, std::invalid_argument);
}

TEST(PurePursuit, CurvatureOfTheArcThroughTheTarget) {
  PurePursuitConfig cfg;
  cfg.lookahead_time = 0.0;  // fixed 1 m lookahead
  PurePursuitController c(cfg);
  ControlInput in;
  in.speed_ref = 0.5;
  in.path_base = core::Line2(Eigen::Vector2d(0.0, 0.2), Eigen::Vector2d::UnitX());
  // Target (1, 0.2): kappa = 2 * 0.2 / 1.04.
  EXPECT_NEAR(c.compute(in).omega, 0.5 * 2.0 * 0.2 / 1.04, 1e-9);
}

TEST(Configs, RejectBadValues) {
  StanleyConfig s;
  s.k = 0.0;
  EXPECT_THROW(StanleyController{s}, std::invalid_argument);
  LookaheadPidConfig l;
  l.slowdown.stop_distance = 3.0;
  EXPECT_THROW(LookaheadPidController{l}, std::invalid_argument);
  PurePursuitConfig p;
  p.max_lookahead = 0.5;
  EXPECT_THROW(PurePursuitController{p}, std::invalid_argument);
}

}  // namespace
}  // namespace rownav::control
