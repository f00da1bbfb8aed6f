#include "rownav/sim/scripted_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace rownav::sim {
namespace {

/// `n` rows along x from 0 to `len` m, 2 m apart (+ `amp` sin(x / 8)), a vine every metre.
Field rows_field(int n = 4, double len = 30.0, double headland = 6.0, double amp = 0.0) {
  Field f;
  f.row_spacing = 2.0;
  f.headland_width = headland;
  for (int k = 0; k < n; ++k) {
    Row r;
    r.id = k;
    for (double x = 0.0; x <= len + 1e-9; x += 0.5)
      r.polyline.emplace_back(x, 2.0 * k + amp * std::sin(x / 8.0));
    for (int i = 0; i <= static_cast<int>(len); ++i) {
      Plant p;
      p.position = {static_cast<double>(i), 2.0 * k + amp * std::sin(i / 8.0)};
      p.row = k;
      f.plants.push_back(p);
    }
    f.rows.push_back(r);
  }
  return f;
}

double min_row_distance(const Field& f, const Eigen::Vector2d& p) {
  double d = 1e9;
  for (const auto& r : f.rows) d = std::min(d, project_on_polyline(r.polyline, p).distance);
  return d;
}

PathConfig three_corridors(TurnStyle turn = TurnStyle::u_turn) {
  PathConfig c;
  c.corridors = {0, 1, 2};
  c.turn = turn;
  return c;
}

TEST(BuildPath, ThreeCorridorsOnCentreLinesTurnsClearOfRows) {
  const Field f = rows_field();
  const FieldTruth t(f);
  const auto path = build_path(t, three_corridors(), RobotConfig{});
  ASSERT_GT(path.size(), 1000u);
  int in_row = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (i > 0) {
      EXPECT_LE((path[i].p - path[i - 1].p).norm(), 0.0501);
    }
    EXPECT_GT(min_row_distance(f, path[i].p), 0.99) << i;  // turns never cross a row
    if (!path[i].in_row) continue;
    ++in_row;
    double d = 1e9;
    for (int k = 0; k < 3; ++k)
      d = std::min(d, project_on_polyline(t.corridor_centre(0, k), path[i].p).distance);
    EXPECT_LT(d, 0.02);
    EXPECT_EQ(path[i].speed, 1.0);
  }
  EXPECT_NEAR(in_row * 0.05, 90.0, 0.5);  // three 30 m lanes
  EXPECT_EQ(path.back().speed, 0.0);
  EXPECT_NEAR(path.front().p.x(), -2.0, 1e-9);  // lead-in
  // Corridor 1 is driven towards -x.
  EXPECT_NEAR(path.back().p.x(), 31.5, 1e-9);
  EXPECT_NEAR(path.back().p.y(), 5.0, 1e-9);
}

TEST(BuildPath, CarLikeBulbTurnRespectsMinimumRadius) {
  const Field f = rows_field(4, 30.0, 12.0);
  const FieldTruth t(f);
  RobotConfig car;
  car.drive = DriveKind::ackermann;
  car.wheelbase = 1.6;
  car.max_steer_deg = 28.0;  // min radius 3.0 m > spacing / 2
  PathConfig c = three_corridors(TurnStyle::bulb);
  const auto path = build_path(t, c, car);
  double max_curv = 0.0;
  for (std::size_t i = 2; i < path.size(); i += 1) {
    // Curvature from three points 0.1 m apart: 2 sin(angle) / chord.
    const Eigen::Vector2d a = path[i - 2].p, b = path[i - 1].p, d = path[i].p;
    const double cr = (b - a).x() * (d - b).y() - (b - a).y() * (d - b).x();
    max_curv =
        std::max(max_curv, 2.0 * std::abs(cr) / ((b - a).norm() * (d - b).norm() * (d - a).norm()));
    EXPECT_GT(min_row_distance(f, path[i].p), 0.99);
  }
  EXPECT_LT(max_curv, 1.0 / car.min_turn_radius() * 1.01);
  EXPECT_GT(max_curv, 1.0 / (1.2 * car.min_turn_radius()));
  // The default 6 m headland is too short for this turn.
  const Field small = rows_field();
  const FieldTruth ts(small);
  EXPECT_THROW(build_path(ts, c, car), std::invalid_argument);
}

TEST(BuildPath, BadConfigsThrowNamingTheProblem) {
  const Field f = rows_field();
  const FieldTruth t(f);
  PathConfig c;
  c.corridors = {0, 1, 99};
  try {
    build_path(t, c, RobotConfig{});
    FAIL() << "expected a throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "corridors[2]: corridor 99 does not exist in block 0 (0..2)");
  }
  c.corridors = {0};
  c.block = 3;
  EXPECT_THROW(build_path(t, c, RobotConfig{}), std::invalid_argument);
  RobotConfig car;
  car.drive = DriveKind::ackermann;
  EXPECT_THROW(build_path(t, three_corridors(TurnStyle::in_place), car), std::invalid_argument);
  PathConfig w;
  w.waypoints = {{0.0, 1.0}, {50.0, 1.0}};
  try {
    build_path(t, w, RobotConfig{});
    FAIL() << "expected a throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("leaves the field area"), std::string::npos);
  }
}

TEST(BuildPath, WaypointsMarkLanePoints) {
  const Field f = rows_field();
  const FieldTruth t(f);
  PathConfig w;
  w.waypoints = {{-3.0, 1.0}, {10.0, 1.0}};
  const auto path = build_path(t, w, RobotConfig{});
  EXPECT_NEAR(path.size(), 261u, 1u);
  EXPECT_FALSE(path.front().in_row);
  EXPECT_TRUE(path.back().in_row);
}

struct DriveResult {
  bool done = false;
  double rms = 0.0, max_err = 0.0;
  int crushed = 0;
  core::Pose2 final_pose;
};

/// Closed loop: follower on the true pose of a simulated robot; errors measured in lanes once
/// the robot is 3 m past the lane entry.
DriveResult drive(const Field& f, const PathConfig& pc, const RobotConfig& rc, std::uint64_t seed) {
  const FieldTruth t(f);
  auto path = build_path(t, pc, rc);
  const Eigen::Vector2d d = (path[1].p - path[0].p).normalized();
  Robot robot(rc, seed, core::Pose2(path[0].p.x(), path[0].p.y(), std::atan2(d.y(), d.x())));
  PathFollower follower(std::move(path));
  CrushCounter crush(f);
  DriveResult r;
  double sum2 = 0.0;
  int n = 0;
  for (int i = 0; i < 30000 && !follower.done(); ++i) {
    robot.step(follower.command(robot.state().pose), 0.02);
    crush.update(robot.footprint_world());
    const auto& p = robot.state().pose;
    const GroundTruth g = t.at(p, robot.state().stamp, 0.0);
    if (g.place != Place::lane || p.x < 3.0 || p.x > 27.0) continue;
    sum2 += g.lateral_error * g.lateral_error;
    r.max_err = std::max(r.max_err, std::abs(g.lateral_error));
    ++n;
  }
  r.done = follower.done();
  r.rms = std::sqrt(sum2 / std::max(n, 1));
  r.crushed = crush.total();
  r.final_pose = robot.state().pose;
  std::printf("drive: t %.1f s, rms %.4f m, max %.4f m, n %d, crushed %d\n", robot.state().stamp,
              r.rms, r.max_err, n, r.crushed);
  return r;
}

TEST(PathFollower, SkidSteerWithSlipFollowsUTurns) {
  const DriveResult r = drive(rows_field(), three_corridors(), RobotConfig{}, 7);
  EXPECT_TRUE(r.done);
  EXPECT_LT(r.rms, 0.02);
  EXPECT_LT(r.max_err, 0.05);
  EXPECT_EQ(r.crushed, 0);
  EXPECT_NEAR(r.final_pose.x, 31.5, 0.15);
  EXPECT_NEAR(r.final_pose.y, 5.0, 0.1);
}

TEST(PathFollower, SkidSteerOnCurvedRows) {
  const Field f = rows_field(4, 30.0, 6.0, 1.5);
  const FieldTruth t(f);
  for (const auto& pt : build_path(t, three_corridors(), RobotConfig{}))
    EXPECT_GT(min_row_distance(f, pt.p), 0.95);
  const DriveResult r = drive(f, three_corridors(), RobotConfig{}, 12);
  EXPECT_TRUE(r.done);
  EXPECT_LT(r.max_err, 0.05);
  EXPECT_EQ(r.crushed, 0);
}

TEST(PathFollower, SkidSteerInPlaceTurns) {
  const DriveResult r = drive(rows_field(), three_corridors(TurnStyle::in_place), RobotConfig{}, 8);
  EXPECT_TRUE(r.done);
  EXPECT_LT(r.max_err, 0.05);
  EXPECT_EQ(r.crushed, 0);
}

TEST(PathFollower, CarLikeBulbTurns) {
  RobotConfig car;
  car.drive = DriveKind::ackermann;
  car.wheelbase = 1.6;
  car.max_steer_deg = 28.0;
  car.alpha = 0.97;
  car.length = 2.2;
  car.width = 1.2;
  car.base_to_front = 1.9;
  const DriveResult r = drive(rows_field(4, 30.0, 12.0), three_corridors(TurnStyle::bulb), car, 9);
  EXPECT_TRUE(r.done);
  EXPECT_LT(r.max_err, 0.05);
  EXPECT_EQ(r.crushed, 0);
}

TEST(PathFollower, DeterministicForASeed) {
  const DriveResult a = drive(rows_field(), three_corridors(), RobotConfig{}, 11);
  const DriveResult b = drive(rows_field(), three_corridors(), RobotConfig{}, 11);
  EXPECT_EQ(a.final_pose.x, b.final_pose.x);
  EXPECT_EQ(a.final_pose.theta, b.final_pose.theta);
  EXPECT_EQ(a.rms, b.rms);
}

TEST(PathFollower, EmptyPathIsDone) {
  PathFollower f({});
  EXPECT_TRUE(f.done());
  const core::Twist2 c = f.command(core::Pose2());
  EXPECT_EQ(c.v, 0.0);
  EXPECT_EQ(f.progress(), 1.0);
}

}  // namespace
}  // namespace rownav::sim
