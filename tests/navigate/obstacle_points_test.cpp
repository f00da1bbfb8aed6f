#include "rownav/navigate/obstacle_points.hpp"

#include <gtest/gtest.h>

#include "common/flat_ground.hpp"

#include <cmath>

namespace rownav::navigate {
namespace {

using test::flat_ground;
using test::pt;

TEST(ObstaclePoints, WeedsBelowTheBandAreGroundCoverAPersonOrABoxIsAnObstacle) {
  const ObstacleBandConfig band;
  core::PointCloud c;
  for (float z : {0.05f, 0.15f, 0.25f}) c.points.push_back(pt(1.5f, 0.0f, z));  // weed tuft
  for (float z = 0.1f; z < 1.7f; z += 0.1f) c.points.push_back(pt(2.0f, 0.1f, z));  // person
  for (float z : {0.05f, 0.15f, 0.25f, 0.35f, 0.45f}) c.points.push_back(pt(3.0f, -0.2f, z));  // box
  c.points.push_back(pt(2.0f, 0.0f, 3.0f));                  // a wire above the robot
  c.points.push_back(pt(-1.0f, 0.0f, 1.0f));                 // behind
  c.points.push_back(pt(2.0f, 2.5f, 1.0f));                  // beside, outside the band
  c.points.push_back(pt(std::nanf(""), 0.0f, 1.0f));         // not a point
  const auto pts = obstacle_points(c, flat_ground(), band);
  int person = 0, box = 0, other = 0;
  for (const auto& p : pts) {
    if (std::abs(p.x() - 2.0f) < 1e-6f && std::abs(p.y() - 0.1f) < 1e-6f)
      ++person;
    else if (std::abs(p.x() - 3.0f) < 1e-6f)
      ++box;
    else
      ++other;
  }
  EXPECT_GE(person, 13);  // 0.3 .. 1.6 m
  EXPECT_EQ(box, 2);      // 0.35 and 0.45 m: a 0.45 m box still counts
  EXPECT_EQ(other, 0);    // no weed, wire, point behind / beside, NaN
}

TEST(ObstaclePoints, HeightsAreAboveTheLocalGroundOnASlope) {
  // Ground rising 10 % along x: a 0.2 m weed at x = 4 sits at z = 0.6, below the band.
  std::vector<core::PointXYZIRT> floor;
  for (float x = -2.0f; x <= 8.0f; x += 0.25f)
    for (float y = -3.0f; y <= 3.0f; y += 0.25f) floor.push_back(pt(x, y, 0.1f * x));
  preprocess::GroundEstimator g;
  g.estimate(floor);
  core::PointCloud c;
  c.points.push_back(pt(4.0f, 0.0f, 0.6f));  // weed
  c.points.push_back(pt(4.0f, 0.2f, 1.2f));  // 0.8 m above the slope
  const auto pts = obstacle_points(c, g, ObstacleBandConfig{});
  ASSERT_EQ(pts.size(), 1u);
  EXPECT_FLOAT_EQ(pts[0].y(), 0.2f);
}

TEST(ObstaclePoints, WhatIsHigherThanTheRobotsTopPassesOverIt) {
  // Issue 10: a crown hanging 0.9 m over the corridor passes over a robot whose top is 0.85 m;
  // the trunk of a person under it does not.
  ObstacleBandConfig band;
  core::PointCloud c;
  for (float y = -0.3f; y <= 0.3f; y += 0.1f) c.points.push_back(pt(1.0f, y, 0.9f));  // crown
  for (float z = 0.4f; z < 1.7f; z += 0.1f) c.points.push_back(pt(2.0f, 0.0f, z));    // person
  const auto all = obstacle_points(c, flat_ground(), band);
  const auto under = obstacle_points(c, flat_ground(), band, 0.85);
  EXPECT_EQ(all.size(), 7u + 13u);
  ASSERT_EQ(under.size(), 5u);  // the person's 0.4 .. 0.8 m
  for (const auto& p : under) EXPECT_FLOAT_EQ(p.x(), 2.0f);
}

}  // namespace
}  // namespace rownav::navigate
