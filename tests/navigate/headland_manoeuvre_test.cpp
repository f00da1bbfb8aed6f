#include "rownav/navigate/headland_manoeuvre.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace rownav::navigate {
namespace {

/// A block of rows ending on the line x = 0 (turn frame = odom here): row k's centre at
/// y = (k + 1/2) spacing, its canopy 2 half_width wide, one row end possibly missing.
struct RowEndsScene {
  double spacing = 1.67;    ///< [m] true centre-to-centre spacing
  double half_width = 0.3;  ///< [m] canopy half width at the row end
  double noise = 0.03;      ///< [m] standard deviation of a row end's across position
  double range = 8.0;       ///< [m] row ends farther from the robot are not seen
  int missing = 99;         ///< index k of a row end not seen (a missing plant at the end)
  /// [m] y of other things on the row-end line (a weed, a post), each seen once the robot has
  /// passed it (hidden before by the row end beside it)
  std::vector<double> clutter;
  double offset = 0.0;  ///< [m] every row's y shifted by this (the exit centre estimated off)
  /// [m] y of things glimpsed on the row-end line in one frame out of `glimpse_every`
  std::vector<double> glimpsed;
  int glimpse_every = 20;

  /// Row ends one frame sees from `robot`: each row's end, biased towards the robot by half the
  /// offset of its end cap's nearest point (the end slice's centroid takes the cap and the side
  /// facing the robot; the re-anchoring's midpoint cancels the bias once abeam).
  std::vector<Eigen::Vector2d> seen(const Eigen::Vector2d& robot, std::mt19937& rng,
                                    int frame) const {
    std::normal_distribution<double> n(0.0, noise);
    std::vector<Eigen::Vector2d> out;
    for (int k = -4; k <= 5; ++k) {
      if (k == missing) continue;
      const double c = (k + 0.5) * spacing + offset;
      const Eigen::Vector2d p(
          0.0, c + 0.5 * std::clamp(robot.y() - c, -half_width, half_width) + n(rng));
      if ((p - robot).norm() < range) out.push_back(p);
    }
    for (const double y : clutter)
      if (std::abs(robot.y()) > std::abs(y) && robot.y() * y > 0.0)
        out.emplace_back(0.0, y + n(rng));
    if (frame % glimpse_every == 0)
      for (const double y : glimpsed) out.emplace_back(0.0, y + n(rng));
    return out;
  }
};

/// Drives a manoeuvre (unicycle, 0.02 s steps, a LiDAR frame every 5th step) from the exit
/// corridor's centre line 1 m past the row ends, where the turn starts; returns the final pose.
core::Pose2 drive(HeadlandManoeuvre& m, const RowEndsScene& scene, std::uint32_t seed) {
  std::mt19937 rng(seed);
  core::Pose2 T(1.0, 0.0, 0.0);
  for (int i = 0; i < 20000 && !m.done(); ++i) {
    const auto ends =
        i % 5 == 0 ? scene.seen(T.translation(), rng, i / 5) : std::vector<Eigen::Vector2d>{};
    const auto s = m.step(T, ends);
    T = T * core::Pose2(s.cmd.v * 0.02, 0.0, s.cmd.omega * 0.02);
  }
  return T;
}

// The in-row spacing of an opaque canopy seen from inside its corridor can be 15 % short (the
// crown seen from below, issue 10: 1.41 m for 1.67 m rows); the row ends seen from the headland
// show each canopy's full width. Random spacings and in-row errors, both sides, one and two
// corridors over. The target falls short by up to 5 % of the spacing whatever the in-row error:
// a row end's mean over the frames keeps the bias of its first, oblique views (a mean over its
// latest 10 frames removed it here but lost 5 runs of the zoo; BENCHMARK.md).
/// 24 random blocks (spacing 1.4-3.6 m), both sides, one and two corridors over, the in-row
/// spacing a random factor in [lo, hi] of the true one: the manoeuvre ends in the target corridor.
void expect_reanchored(double lo, double hi, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> spacing(1.4, 3.6), factor(lo, hi);
  for (int trial = 0; trial < 24; ++trial) {
    RowEndsScene scene;
    scene.spacing = spacing(rng);
    scene.half_width = 0.15 * scene.spacing;
    const double in_row = scene.spacing * factor(rng);
    const int shift = 1 + trial % 2;
    const TurnSide side = trial % 4 < 2 ? TurnSide::left : TurnSide::right;
    const double truth = side_sign(side) * shift * scene.spacing;
    HeadlandManoeuvre m({}, {TurnKind::in_place, 0.0}, core::Pose2(), shift, side, in_row, 1.0);
    const core::Pose2 T = drive(m, scene, 100 + trial);
    SCOPED_TRACE("trial " + std::to_string(trial) + ": spacing " + std::to_string(scene.spacing) +
                 ", in-row " + std::to_string(in_row) + ", shift " + std::to_string(shift));
    ASSERT_TRUE(m.done());
    EXPECT_NEAR(m.pole_spacing(), scene.spacing, 0.05 * scene.spacing);
    EXPECT_NEAR(m.target_y(), truth, 0.06 * scene.spacing);
    // Inside the corridor with room to spare: its clear half width is 0.35 spacings here, a
    // skid-steer robot's half width 0.2-0.25 spacings in a narrow vineyard.
    EXPECT_NEAR(T.y, truth, 0.1 * scene.spacing);
  }
}

TEST(HeadlandManoeuvre, ReanchorsOnTheRowEndsWhenTheInRowSpacingIsUpToAFifthOff) {
  expect_reanchored(0.8, 1.2, 7);
}

// A wide vineyard whose canopy tops stand above the sensor: seen from inside the corridor only
// the two corridor rows' inner top edges, 1.99 m for 2.94 m rows (zoo:1:76, a ratio 1.48); the
// row ends seen from the headland still give the spacing (issue 10).
TEST(HeadlandManoeuvre, ReanchorsOnTheRowEndsWhenTheInRowSpacingIsAThirdShort) {
  expect_reanchored(1.0 / 1.5, 1.0 / 1.45, 11);
}

TEST(HeadlandManoeuvre, RowEndSpacingCountsAMissingRowEndAsTwoSpacings) {
  RowEndsScene scene;
  scene.missing = 3;  // beyond the target: its neighbours' difference spans two spacings
  HeadlandManoeuvre m({}, {TurnKind::in_place, 0.0}, core::Pose2(), 1, TurnSide::left,
                      0.85 * scene.spacing, 1.0);
  drive(m, scene, 3);
  ASSERT_TRUE(m.done());
  EXPECT_NEAR(m.pole_spacing(), scene.spacing, 0.05 * scene.spacing);
  EXPECT_NEAR(m.target_y(), scene.spacing, 0.15);
}

// zoo:1:61 (2.12 m rows, in-row spacing 1.84 m), the second turn, to the right: the row ends
// merged when the target was re-anchored (y in the turn frame, frames seen), replayed. The
// corridor's far row end across the robot read 0.42 (its nearest point, 0.64 m towards the
// robot) and something on the row-end line at -2.21 split the target's two flanks (-1.10,
// -3.20) in two; the median of the row ends' differences read 1.51 m, the flanks became that
// thing and the near row end, and the robot entered 0.47 m off towards a post (issue 10).
TEST(HeadlandManoeuvre, SomethingMidwayBetweenTwoRowEndsDoesNotHalveTheirSpacing) {
  const std::vector<std::pair<double, int>> seen{{0.42, 75},  {-1.10, 64}, {-2.21, 24},
                                                 {-3.20, 65}, {-5.27, 47}, {-7.35, 41}};
  HeadlandManoeuvre m({}, {TurnKind::in_place, 0.0}, core::Pose2(), 1, TurnSide::right, 1.84, 1.0);
  const core::Pose2 T(0.5, -1.08, -std::numbers::pi / 2.0);  // in the headland, abeam
  for (int frame = 0; frame < 75; ++frame) {
    std::vector<Eigen::Vector2d> ends;
    for (const auto& [y, n] : seen)
      if (frame < n) ends.emplace_back(0.0, y);
    m.step(T, ends);
  }
  EXPECT_NEAR(m.pole_spacing(), 2.12, 0.1);
  EXPECT_NEAR(m.target_y(), -2.15, 0.15);  // midway between -1.10 and -3.20
}

TEST(HeadlandManoeuvre, AFlankIsTheRowEndNearestItsExpectedPlaceNotAWeedInTheGate) {
  // zoo:1:20: the turn frame 0.26 m off (the exit corridor's centre as tracked), a weed inside
  // the anchor gate on the other side of the near flank's expected place took that flank in
  // every other frame and the target jumped by 0.4 m.
  for (const int side : {1, -1}) {
    RowEndsScene scene;
    scene.offset = side * 0.15 * scene.spacing;
    scene.clutter = {side * 0.22 * scene.spacing};
    HeadlandManoeuvre m({}, {TurnKind::in_place, 0.0}, core::Pose2(), 1,
                        side > 0 ? TurnSide::left : TurnSide::right, scene.spacing, 1.0);
    drive(m, scene, 11);
    ASSERT_TRUE(m.done());
    EXPECT_NEAR(m.target_y(), side * scene.spacing + scene.offset, 0.1) << "side " << side;
  }
}

TEST(HeadlandManoeuvre, AThingGlimpsedInAFewFramesIsNoRowEnd) {
  // zoo:1:70: a weed seen twice near the target corridor's centre, among row ends seen 30-60
  // times, halved two of the row ends' differences and their spacing fell outside the tolerance.
  RowEndsScene scene;
  scene.range = 4.0;  // four or five row ends in view, as there
  scene.glimpsed = {1.05 * scene.spacing};
  HeadlandManoeuvre m({}, {TurnKind::in_place, 0.0}, core::Pose2(), 1, TurnSide::left,
                      0.85 * scene.spacing, 1.0);
  drive(m, scene, 13);
  ASSERT_TRUE(m.done());
  EXPECT_NEAR(m.pole_spacing(), scene.spacing, 0.05 * scene.spacing);
  EXPECT_NEAR(m.target_y(), scene.spacing, 0.06 * scene.spacing);
}

TEST(HeadlandManoeuvre, RowEndsOutsideTheToleranceLeaveTheInRowSpacing) {
  // Row ends twice the in-row spacing apart (every other row end missed, or another block's
  // rows) are refused: the turn keeps the in-row spacing and is not re-anchored on them.
  RowEndsScene scene;
  scene.spacing = 4.0;
  HeadlandManoeuvre m({}, {TurnKind::in_place, 0.0}, core::Pose2(), 1, TurnSide::left, 2.0, 1.0);
  drive(m, scene, 5);
  ASSERT_TRUE(m.done());
  EXPECT_DOUBLE_EQ(m.pole_spacing(), 2.0);
  EXPECT_DOUBLE_EQ(m.target_y(), 2.0);
}

TEST(HeadlandManoeuvre, RowEndsCloserThanTheInRowSpacingAreHeldToTheTighterTolerance) {
  // Clutter on the row-end line shortens the row ends' spacing: 1.4 m row ends against a 2.0 m
  // in-row spacing (a ratio 1.43, which the long side would pass) are refused.
  RowEndsScene scene;
  scene.spacing = 1.4;
  HeadlandManoeuvre m({}, {TurnKind::in_place, 0.0}, core::Pose2(), 1, TurnSide::left, 2.0, 1.0);
  drive(m, scene, 5);
  ASSERT_TRUE(m.done());
  EXPECT_DOUBLE_EQ(m.pole_spacing(), 2.0);
}

TEST(HeadlandManoeuvre, ConfigRejectsFewerThanTwoSpacingPolesANegativeToleranceAndAShareAboveOne) {
  ManoeuvreConfig c;
  c.spacing_poles = 1;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = {};
  c.spacing_tolerance = -0.1;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = {};
  c.spacing_tolerance_long = -0.1;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = {};
  c.pole_share = 1.5;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::navigate
