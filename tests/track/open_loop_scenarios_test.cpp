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

// Bounds per scenario for line_ekf and model_filter with hough_skew (sweeps levelled with the
// accelerometer, Localizer odometry but in truth_drift): the worse of the two measured RMSEs
// (comment: line_ekf / model_filter, lateral mm, heading deg) with ~25 % margin.
const std::map<std::string, Bound> kBounds = {
    {"straight", {0.015, 0.62}},     // 6.3 / 11.6 mm; 0.49 / 0.43 deg
    {"curved", {0.027, 1.4}},        // 12.5 / 20.9 mm; 1.09 / 0.98 deg
    {"gaps_3", {0.018, 0.6}},        // 6.0 / 13.8 mm; 0.47 / 0.29 deg
    {"gaps_5", {0.013, 0.57}},       // 6.8 / 9.6 mm; 0.45 / 0.38 deg
    {"weeds_some", {0.014, 0.6}},    // 6.1 / 10.8 mm; 0.48 / 0.41 deg
    {"weeds_many", {0.016, 0.62}},   // 7.1 / 12.1 mm; 0.49 / 0.42 deg
    {"slip_drift", {0.015, 1.2}},    // 9.5 / 11.9 mm; 0.95 / 0.41 deg
    {"truth_drift", {0.015, 0.57}},  // 5.1 / 11.6 mm; 0.45 / 0.43 deg
};
// model_matching keeps its models in a frame fixed by the odometry (Nehme 2021 sec. 3.3), so it
// inherits the Localizer's drift: with the nominal skid-steer kinematics the wheels read ~11 %
// too far and ~0.7 deg/s of yaw rate, and the EKF's gyro bias follows them (0.025 rad/s against
// a true 0.002), measured on "straight". It then carries a ~5 cm lateral / ~1 deg heading error
// (55 mm / 0.95 deg; 142 mm / 2.7 deg with heavy slip; 30 mm / 0.6 deg with truth_drift): only
// its loose bound is checked until the Localizer's bias estimation is fixed.
const Bound kModelMatchingBound = {0.18, 3.5};

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
      const Bound b = tracker == "model_matching" ? kModelMatchingBound : kBounds.at(s.name);
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
