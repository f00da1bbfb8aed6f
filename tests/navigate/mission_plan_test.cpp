#include "rownav/navigate/mission_plan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "rownav/navigate/headland_manoeuvre.hpp"

namespace rownav::navigate {
namespace {

TEST(MissionPlan, SweepOrderWithSkipsAndStopAfter) {
  MissionPlan p;
  p.skip = {2};
  p.stop_after = 3;
  EXPECT_EQ(resolve_order(p, 6), (std::vector<int>{0, 1, 3}));
  p.stop_after = 0;
  EXPECT_EQ(resolve_order(p, 4), (std::vector<int>{0, 1, 3}));
}

TEST(MissionPlan, RejectsMissingCorridorAndBadFields) {
  MissionPlan p;
  p.corridors = {0, 7};
  EXPECT_THROW(resolve_order(p, 5), std::invalid_argument);
  p.corridors = {};
  p.stop_after = -1;
  EXPECT_THROW(p.validate(), std::invalid_argument);
}

TEST(MissionPlan, TurnSidesAlternateInASweep) {
  const auto c = corridor_changes({0, 1, 2, 3}, TurnSide::left);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].side, TurnSide::left);
  EXPECT_EQ(c[1].side, TurnSide::right);
  EXPECT_EQ(c[2].side, TurnSide::left);
  EXPECT_EQ(c[1].shift, 1);
}

TEST(Manoeuvre, CarLikeRobotSkipsRowsOrBulbs) {
  const TurnAbility car{false, 3.0};
  EXPECT_EQ(min_feasible_shift(1.8, 3.0), 5);  // 5 * 1.8 >= 2 * 1.25 * 3
  const TurnPlan bulb = choose_turn(ManoeuvreChoice::automatic, 1, 1.8, car);
  EXPECT_EQ(bulb.kind, TurnKind::bulb);
  EXPECT_FALSE(bulb.can_rotate);
  EXPECT_EQ(choose_turn(ManoeuvreChoice::automatic, 4, 1.8, car).kind, TurnKind::bulb);
  const TurnPlan far = choose_turn(ManoeuvreChoice::automatic, 5, 1.8, car);
  EXPECT_EQ(far.kind, TurnKind::u_turn);
  EXPECT_DOUBLE_EQ(far.radius, 3.75);  // 25 % above the minimum radius
  // Lan 2021: radius = spacing / 2 for a robot that can.
  const TurnPlan u = choose_turn(ManoeuvreChoice::u_turn, 1, 3.0, {true, 0.0});
  EXPECT_DOUBLE_EQ(u.radius, 1.5);
  const auto order = skip_order(10, 2);
  for (std::size_t i = 1; i < order.size(); ++i) EXPECT_GE(std::abs(order[i] - order[i - 1]), 2);
}

TEST(Manoeuvre, InPlaceRotationReachesNinetyDegrees) {
  HeadlandManoeuvre m({}, {TurnKind::in_place, 0.0}, core::Pose2(), 1, TurnSide::left, 2.0, 1.0);
  core::Pose2 T(1.0, 0.0, 0.0);
  for (int i = 0; i < 1000 && std::abs(T.theta - M_PI / 2) > 0.035; ++i) {
    const auto s = m.step(T, {});
    T = T * core::Pose2(s.cmd.v * 0.01, 0.0, s.cmd.omega * 0.01);
  }
  EXPECT_NEAR(T.theta, M_PI / 2, 0.04);
}

TEST(Manoeuvre, UTurnEndsInTheAdjacentCorridorHeadingBack) {
  HeadlandManoeuvre m({}, {TurnKind::u_turn, 1.0}, core::Pose2(), 1, TurnSide::left, 2.0, 1.0);
  core::Pose2 T(1.0, 0.0, 0.0);
  for (int i = 0; i < 5000 && !m.done(); ++i) {
    const auto s = m.step(T, {});
    T = T * core::Pose2(s.cmd.v * 0.01, 0.0, s.cmd.omega * 0.01);
  }
  EXPECT_TRUE(m.done());
  EXPECT_NEAR(T.y, 2.0, 0.15);
  EXPECT_NEAR(std::abs(T.theta), M_PI, 0.2);
}

// A bicycle model whose steering angle is rate limited (car_like.yaml: 1.6 m wheelbase, 28 deg,
// 40 deg/s) drives the command; returns the final pose after at most `steps` of 0.01 s.
core::Pose2 drive_car(HeadlandManoeuvre& m, core::Pose2 T, int steps) {
  const double wheelbase = 1.6, max_steer = 28.0 * M_PI / 180.0, rate = 40.0 * M_PI / 180.0;
  double steer = 0.0;
  for (int i = 0; i < steps && !m.done(); ++i) {
    const auto s = m.step(T, {});
    double target = steer;
    if (std::abs(s.cmd.v) > 1e-3) target = std::atan(wheelbase * s.cmd.omega / s.cmd.v);
    target = std::clamp(target, -max_steer, max_steer);
    steer += std::clamp(target - steer, -rate * 0.01, rate * 0.01);
    T = T * core::Pose2(s.cmd.v * 0.01, 0.0, s.cmd.v * std::tan(steer) / wheelbase * 0.01);
  }
  return T;
}

TEST(Manoeuvre, CarLikeBulbFinishesInTheAdjacentCorridor) {
  // Closed loop the bulb used r = r_min and a zero-speed yaw command when the robot lagged the
  // arc: a car-like robot stood still for ever (issue 5, closed_loop_wide, serve_all).
  const TurnAbility car{false, 1.6 / std::tan(28.0 * M_PI / 180.0)};
  const TurnPlan plan = choose_turn(ManoeuvreChoice::automatic, 1, 2.8, car);
  ASSERT_EQ(plan.kind, TurnKind::bulb);
  HeadlandManoeuvre m({}, plan, core::Pose2(), 1, TurnSide::left, 2.8, 1.2);
  const core::Pose2 T = drive_car(m, core::Pose2(1.2, 0.0, 0.0), 20000);
  EXPECT_TRUE(m.done());
  EXPECT_NEAR(T.y, 2.8, 0.3);
  EXPECT_NEAR(std::abs(T.theta), M_PI, 0.3);
}

}  // namespace
}  // namespace rownav::navigate
