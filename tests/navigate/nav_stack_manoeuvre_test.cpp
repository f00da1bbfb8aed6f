// NavStack tells the tracker when the robot manoeuvres in the headland, so that a tracker keeps
// what it learnt of the field's geometry through the turn's frames (issue 10: a model filter
// learnt a 0.61 m "lattice" in 2.8 m rows from them and lost the rows after the turn).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>
#include <vector>

#include "common/planar_scan.hpp"
#include "common/synthetic_rows.hpp"
#include "rownav/io/controller_registry.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/navigate/nav_stack.hpp"
#include "rownav/track/raw_corridor.hpp"

namespace rownav::navigate {
namespace {

/// The raw corridor tracker, logging the manoeuvre flag NavStack set before each update.
class SpyTracker : public track::RowTracker {
 public:
  explicit SpyTracker(std::vector<bool>* log) : log_(log) {}
  std::string_view name() const override { return "spy"; }
  track::RowTracking update(const core::RowObservation& obs, const core::Pose2& T) override {
    log_->push_back(manoeuvring_);
    return inner_.update(obs, T);
  }
  void reset() override { inner_.reset(); }
  void set_manoeuvring(bool manoeuvring) override { manoeuvring_ = manoeuvring; }

 private:
  std::vector<bool>* log_;
  track::RawCorridorTracker inner_;
  bool manoeuvring_ = false;
};

TEST(NavStackManoeuvre, TheTrackerIsToldOfEveryFrameOfAHeadlandTurnAndOfNoOtherFrame) {
  std::vector<bool> flags;
  NavStackParts parts;
  parts.pipeline =
      std::make_unique<detect::DetectionPipeline>(io::make_pipeline("parallel_lines", ""));
  parts.tracker = std::make_unique<SpyTracker>(&flags);
  parts.controller = io::make_controller("stanley", "");
  NavStack s(NavStackConfig{}, std::move(parts), {0, 1}, TurnSide::left);
  // Four rows 1.8 m apart ending 8 m ahead of the start; the wheels roll straight on at
  // 0.5 m/s whatever the command (the stack's states, not the motion, are under test).
  const double row_end = 8.0, v = 0.5;
  const localize::WheelOdometryConfig w;
  const double ticks_per_m = w.ticks_per_rev / (2.0 * std::numbers::pi * w.wheel_radius);
  NavState state = NavState::in_row;
  std::vector<NavState> state_at_frame;  // the state the stack was in when each frame came
  bool turned = false;
  for (int k = 1; k <= 4000 && !turned; ++k) {
    const double t = 0.01 * k, x = v * t;
    if (k % 2 == 0) {
      const auto ticks = static_cast<std::int64_t>(std::llround(x * ticks_per_m));
      s.on_encoders({t, ticks, ticks, 0.0});
    }
    if (k % 4 == 0) {
      test::SyntheticRows rows;
      rows.seed = static_cast<std::uint64_t>(k);
      rows.x_min = -3.0;
      rows.x_max = row_end - x;
      const auto pts =
          rows.x_max > rows.x_min ? test::make_rows(rows).points : std::vector<Eigen::Vector2f>{};
      s.on_scan(test::planar_scan(pts, t - 0.04));
    }
    const NavCommand c = s.command(t);
    if (c.frame && c.frame->tracking) state_at_frame.push_back(state);
    state = c.state;
    turned = state == NavState::turning &&
             std::count(state_at_frame.begin(), state_at_frame.end(), NavState::turning) >= 5;
    ASSERT_NE(state, NavState::safe_stop) << t;
  }
  ASSERT_TRUE(turned) << "the stack never turned";
  ASSERT_EQ(flags.size(), state_at_frame.size());
  for (std::size_t i = 0; i < flags.size(); ++i) {
    const bool manoeuvre =
        state_at_frame[i] == NavState::turning || state_at_frame[i] == NavState::headland;
    EXPECT_EQ(flags[i], manoeuvre) << "frame " << i;
  }
}

}  // namespace
}  // namespace rownav::navigate
