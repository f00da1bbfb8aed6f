// Issue 10: the ground cover the robot drives through sets the obstacle stop's lowest height.
#include "rownav/navigate/ground_cover.hpp"

#include <gtest/gtest.h>

#include "common/flat_ground.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

namespace rownav::navigate {
namespace {

using test::flat_ground;
using test::pt;

/// A sweep with weeds of random heights up to `tallest` behind / beside the robot, and
/// optionally a box of `box` m right ahead (inside the stop box, outside the cover region).
core::PointCloud weedy_sweep(double tallest, double box, std::mt19937_64& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  core::PointCloud c;
  for (int w = 0; w < 6; ++w) {
    const float x = -3.5f + 3.0f * u(rng), y = -0.4f + 0.8f * u(rng);
    const float h = static_cast<float>(tallest) * (0.7f + 0.3f * u(rng));
    for (float z = 0.05f; z <= h; z += 0.05f) c.points.push_back(pt(x, y, z));
  }
  for (float z = 0.05f; z <= box; z += 0.05f)
    for (float y = -0.2f; y <= 0.2f; y += 0.05f) c.points.push_back(pt(0.8f, y, z));
  return c;
}

const CoverRegion kRobot{0.45, 0.3};

TEST(GroundCover, TallWeedsBesideAndBehindRaiseTheObstacleHeightUpToTheCap) {
  const auto ground = flat_ground();
  for (double tallest : {0.4, 0.5, 0.6}) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(tallest * 100));
    GroundCoverEstimator cover;
    for (int f = 0; f < 40; ++f) cover.update(weedy_sweep(tallest, 0.0, rng), ground, kRobot);
    EXPECT_GT(cover.obstacle_min_height(0.3), tallest) << tallest;  // the weeds pass
    EXPECT_LE(cover.obstacle_min_height(0.3), GroundCoverConfig{}.cap);
  }
  // Taller than the cap (a hedge of 1.5 m beside the robot): a person still counts above it.
  std::mt19937_64 rng(3);
  GroundCoverEstimator cover;
  for (int f = 0; f < 40; ++f) cover.update(weedy_sweep(1.5, 0.0, rng), ground, kRobot);
  EXPECT_DOUBLE_EQ(cover.obstacle_min_height(0.3), GroundCoverConfig{}.cap);
}

TEST(GroundCover, AClearCorridorKeepsTheBandAndABoxAheadCannotRaiseItsOwnThreshold) {
  const auto ground = flat_ground();
  std::mt19937_64 rng(1);
  GroundCoverEstimator cover;
  // Bare ground behind (weeds of 0 m: nothing) and a 0.45 m box in the stop box ahead.
  for (int f = 0; f < 40; ++f) cover.update(weedy_sweep(0.0, 0.45, rng), ground, kRobot);
  EXPECT_DOUBLE_EQ(cover.cover(), 0.0);
  EXPECT_DOUBLE_EQ(cover.obstacle_min_height(0.3), 0.3);  // the box's 0.3-0.45 m still count
}

TEST(GroundCover, AFewWeedFramesDoNotMoveTheMedianAndResetForgets) {
  const auto ground = flat_ground();
  std::mt19937_64 rng(2);
  GroundCoverEstimator cover;
  for (int f = 0; f < 20; ++f) cover.update(weedy_sweep(0.0, 0.0, rng), ground, kRobot);
  for (int f = 0; f < 5; ++f) cover.update(weedy_sweep(0.6, 0.0, rng), ground, kRobot);
  EXPECT_DOUBLE_EQ(cover.obstacle_min_height(0.3), 0.3);
  for (int f = 0; f < 30; ++f) cover.update(weedy_sweep(0.6, 0.0, rng), ground, kRobot);
  EXPECT_GT(cover.obstacle_min_height(0.3), 0.5);
  cover.reset();
  EXPECT_DOUBLE_EQ(cover.obstacle_min_height(0.3), 0.3);
}

TEST(GroundCover, DisabledOrNonFiniteInputChangesNothing) {
  const auto ground = flat_ground();
  GroundCoverConfig off;
  off.enabled = false;
  GroundCoverEstimator cover(off);
  std::mt19937_64 rng(4);
  for (int f = 0; f < 40; ++f) cover.update(weedy_sweep(0.6, 0.0, rng), ground, kRobot);
  EXPECT_DOUBLE_EQ(cover.obstacle_min_height(0.3), 0.3);
  GroundCoverEstimator on;
  core::PointCloud bad;
  for (int i = 0; i < 50; ++i) bad.points.push_back(pt(std::nanf(""), 0.0f, 0.5f));
  on.update(bad, ground, kRobot);
  EXPECT_DOUBLE_EQ(on.cover(), 0.0);
}

TEST(GroundCover, ConfigValidationNamesTheField) {
  GroundCoverConfig c;
  c.quantile = 1.5;
  try {
    c.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("quantile"), std::string::npos);
  }
  c = {};
  c.frames = 0;
  EXPECT_THROW(GroundCoverEstimator{c}, std::invalid_argument);
}

}  // namespace
}  // namespace rownav::navigate
