// SimScore, the sim node's account of a run from the ground truth (rownav_ros/sim_node.hpp).
#include <gtest/gtest.h>

#include "rownav_ros/sim_node.hpp"

namespace {

using rownav::ros_bridge::SimScore;
using rownav::sim::GroundTruth;
using rownav::sim::Place;

/// Adds ground truth at 20 Hz from `t0` for `duration` s in `place` / `corridor`.
double drive(SimScore& s, double t0, double duration, Place place, int corridor, double lateral,
             int crushed = 0) {
  double t = t0;
  for (; t < t0 + duration; t += 0.05) {
    GroundTruth g;
    g.stamp = t, g.place = place, g.corridor = corridor, g.lateral_error = lateral;
    g.plants_crushed = crushed;
    s.add(g);
  }
  return t;
}

TEST(SimScore, CountsTheCorridorsDrivenInOrderAndTheirLateralErrors) {
  SimScore s;
  double t = drive(s, 0.0, 1.0, Place::headland, -1, 0.9);  // the headland does not count
  t = drive(s, t, 5.0, Place::lane, 0, -0.02);
  t = drive(s, t, 1.0, Place::lane, 2, 0.3);  // crossed a lane in < 2 s: not driven
  t = drive(s, t, 3.0, Place::headland, -1, 2.0);
  t = drive(s, t, 5.0, Place::lane, 1, 0.04, 1);
  EXPECT_EQ(s.corridors(), (std::vector<int>{0, 1}));
  // Every lane sample counts for the errors, the short crossing too.
  EXPECT_NEAR(s.max_lateral_error(), 0.3, 1e-12);
  EXPECT_GT(s.mean_lateral_error(), 0.02);
  EXPECT_LT(s.mean_lateral_error(), 0.3);
  EXPECT_EQ(s.plants_crushed(), 1);
  const std::string j = s.json(t, "done", false);
  EXPECT_NE(j.find("\"corridors\": [0, 1]"), std::string::npos) << j;
  EXPECT_NE(j.find("\"state\": \"done\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"timed_out\": false"), std::string::npos) << j;
}

TEST(SimScore, ACorridorLeftAndReEnteredCountsAgainOnlyAfterAnother) {
  SimScore s;
  double t = drive(s, 0.0, 3.0, Place::lane, 0, 0.0);
  t = drive(s, t, 1.0, Place::headland, -1, 0.0);
  t = drive(s, t, 3.0, Place::lane, 0, 0.0);  // the same corridor again: no new entry
  t = drive(s, t, 3.0, Place::lane, 1, 0.0);
  t = drive(s, t, 3.0, Place::lane, 0, 0.0);
  EXPECT_EQ(s.corridors(), (std::vector<int>{0, 1, 0}));
}

TEST(SimScore, NothingDrivenIsAnEmptyScore) {
  const SimScore s;
  EXPECT_TRUE(s.corridors().empty());
  EXPECT_EQ(s.max_lateral_error(), 0.0);
  EXPECT_EQ(s.mean_lateral_error(), 0.0);
  EXPECT_NE(s.json(0.0, "", true).find("\"timed_out\": true"), std::string::npos);
}

}  // namespace
