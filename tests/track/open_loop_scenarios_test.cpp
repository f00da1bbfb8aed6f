// Open-loop scenarios (tests/track/open_loop_harness.hpp): hough_skew + each tracker along one
// simulated vineyard corridor (OS1-16, 10 m rows, 1 m/s), scored against the ground truth.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>

#include "open_loop_harness.hpp"

namespace rownav::test {
namespace {

const OpenLoopRecording& recording(const OpenLoopScenario& s) {
  static std::map<std::string, OpenLoopRecording> cache;
  auto it = cache.find(s.name);
  if (it == cache.end()) it = cache.emplace(s.name, simulate(s)).first;
  return it->second;
}

OpenLoopScenario scenario(const std::string& name) {
  for (const auto& s : open_loop_scenarios())
    if (s.name == name) return s;
  throw std::invalid_argument(name);
}

struct Bound {
  double lat_rmse, head_rmse_deg;
};

// Bounds per scenario for every tracker with hough_skew: the worst tracker's measured RMSE
// (comment: model_matching / line_ekf / model_filter, lateral mm, heading deg) with ~25 % margin.
// The raw hough_skew corridor ("none") already carries a ~2.5 cm mean lateral bias on these
// frames, which no tracker can remove: the 2 cm target is not met yet.
const std::map<std::string, Bound> kBounds = {
    {"straight", {0.045, 0.4}},    // 24.3 / 28.0 / 34.7 mm; 0.25 / 0.28 / 0.28 deg
    {"curved", {0.05, 1.15}},      // 18.6 / 23.1 / 38.8 mm; 0.60 / 0.80 / 0.90 deg
    {"gaps_3", {0.05, 0.55}},      // 26.1 / 29.3 / 39.8 mm; 0.15 / 0.28 / 0.40 deg
    {"gaps_5", {0.055, 0.6}},      // 28.0 / 31.1 / 42.7 mm; 0.16 / 0.34 / 0.45 deg
    {"weeds_some", {0.045, 0.4}},  // 24.3 / 27.7 / 33.8 mm; 0.23 / 0.25 / 0.26 deg
    {"weeds_many", {0.045, 0.4}},  // 25.0 / 28.3 / 34.2 mm; 0.25 / 0.29 / 0.30 deg
    {"slip_drift", {0.07, 1.0}},   // 55.9 / 26.4 / 27.1 mm; 0.79 / 0.53 / 0.42 deg
};

TEST(OpenLoop, EveryTrackerFollowsEveryScenarioWithHoughSkew) {
  for (const auto& s : open_loop_scenarios()) {
    const auto& rec = recording(s);
    ASSERT_GT(rec.clouds.size(), 50u) << s.name;
    for (const std::string tracker : {"none", "model_matching", "line_ekf", "model_filter"}) {
      SCOPED_TRACE(s.name + " " + tracker);
      const OpenLoopScore sc = run_open_loop(rec, s, "hough_skew", tracker);
      std::printf(
          "[open loop] %-11s %-15s lateral mean %.1f RMSE %.1f mm max %.1f mm, heading RMSE %.2f "
          "deg max %.2f deg, lost %d / %d lane frames, coasting %d\n",
          s.name.c_str(), tracker.c_str(), 1000 * sc.lat_mean, 1000 * sc.lat_rmse,
          1000 * sc.lat_max, sc.head_rmse_deg, sc.head_max_deg, sc.lost_in_lane, sc.lane_frames,
          sc.coasting);
      ASSERT_GT(sc.scored, 40);
      if (tracker == "none") continue;  // the raw detector: printed for comparison only
      const Bound b = kBounds.at(s.name);
      EXPECT_LT(sc.lat_rmse, b.lat_rmse);
      EXPECT_LT(sc.head_rmse_deg, b.head_rmse_deg);
      // Up to 3 consecutive missing vines (and everything else here): never lost in the row.
      if (s.gap_length <= 3) {
        EXPECT_EQ(sc.lost_in_lane, 0);
      }
    }
  }
}

TEST(OpenLoop, BlackoutCoastsThenTracksAgain) {
  OpenLoopScenario s = scenario("straight");
  s.blackout_start = 4.0, s.blackout_length = 2.0;
  const auto& rec = recording(scenario("straight"));
  for (const auto& tracker : io::tracker_names()) {
    SCOPED_TRACE(tracker);
    const OpenLoopScore sc = run_open_loop(rec, s, "hough_skew", tracker);
    const double t0 = rec.truth.front().stamp;
    int coasting = 0, tracking_after = 0, lost = 0;
    for (std::size_t i = 0; i < sc.status.size(); ++i) {
      const double t = sc.stamps[i] - t0;
      if (t >= 4.0 && t < 6.0) {
        coasting += sc.status[i] == track::TrackStatus::coasting;
        lost += sc.status[i] == track::TrackStatus::lost;
      }
      if (t >= 6.0 && t < 7.0) tracking_after += sc.status[i] == track::TrackStatus::tracking;
    }
    EXPECT_GE(tracking_after, 8);
    if (tracker == "none") {  // the raw corridor coasts for its 1 s, then reports lost
      EXPECT_GE(coasting, 8);
      EXPECT_GE(lost, 8);
      continue;
    }
    EXPECT_GE(coasting, 18);  // 20 sweeps in 2 s, all carried by odometry
    EXPECT_EQ(lost, 0);
  }
}

}  // namespace
}  // namespace rownav::test
