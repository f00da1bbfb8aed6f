// The map stage in closed loop (issue 12): place accuracy and key location errors against the
// simulator's truth, on hand-made run results and on one short mission with the stage on.
#include "rownav/io/place_metrics.hpp"

#include <gtest/gtest.h>

#include "common/nav_doubles.hpp"
#include "rownav/io/field_builder.hpp"
#include "rownav/io/run_metrics.hpp"
#include "rownav/track/raw_corridor.hpp"

namespace rownav::io {
namespace {

sim::FieldConfig small_vineyard() {
  sim::FieldConfig f;
  f.kind = sim::FieldKind::vineyard;
  f.name = "small";
  f.vineyard.rows = 3;
  f.vineyard.row_length = 12.0;
  f.vineyard.row_spacing = 1.8;
  f.vineyard.stage = sim::GrowthStage::medium;
  f.seed = 3;
  return f;
}

TEST(PlaceMetrics, OutsideCountsAsHeadland) {
  EXPECT_EQ(map_place(sim::Place::lane), map::Place::lane);
  EXPECT_EQ(map_place(sim::Place::alley), map::Place::alley);
  EXPECT_EQ(map_place(sim::Place::headland), map::Place::headland);
  EXPECT_EQ(map_place(sim::Place::outside), map::Place::headland);
}

TEST(PlaceMetrics, AccuracyIsTheFractionOfRightFramesAndKeysAreMeasuredToCorridorEnds) {
  const sim::Field field = build_field(small_vineyard(), ".");
  const sim::FieldTruth truth(field);
  const int block = truth.blocks().front();
  const auto& c0 = truth.corridor_centre(block, 0);
  RunResult run;
  run.places = {{0.0, map::Place::headland, sim::Place::outside},
                {0.1, map::Place::headland, sim::Place::lane},
                {0.2, map::Place::lane, sim::Place::lane},
                {0.3, map::Place::unknown, sim::Place::lane}};
  const Eigen::Vector2d off(0.1, 0.0), far(0.3, 0.4);
  run.key_locations = {{{map::Place::headland, map::Place::lane, {}, 1.0}, c0.front() + off},
                       {{map::Place::lane, map::Place::headland, {}, 2.0}, c0.back() + far}};
  const PlaceMetrics m = place_metrics(run, truth, block);
  EXPECT_EQ(m.frames, 4);
  ASSERT_TRUE(m.accuracy.has_value());
  EXPECT_DOUBLE_EQ(*m.accuracy, 0.5);
  ASSERT_EQ(m.keys.size(), 2u);
  EXPECT_EQ(m.keys[0].to, "lane");
  EXPECT_NEAR(m.keys[0].error, 0.1, 1e-9);
  EXPECT_NEAR(m.keys[1].error, 0.5, 1e-9);
  EXPECT_NEAR(*m.key_error_median, 0.1, 1e-9);
  EXPECT_NEAR(*m.key_error_max, 0.5, 1e-9);
  EXPECT_FALSE(place_metrics(RunResult{}, truth, block).accuracy.has_value());
}

/// Corridor 0 of the small vineyard, the map stage on, a raw-corridor tracker and a
/// proportional controller.
ClosedLoopSetup one_corridor_with_place(const sim::Field& field) {
  ClosedLoopSetup s;
  s.field = &field;
  s.mission.corridors = {0};
  s.detect_config = std::string(ROWNAV_SOURCE_DIR) + "/config/detect/vineyard.yaml";
  s.make_tracker = [] { return std::make_unique<track::RawCorridorTracker>(); };
  s.make_controller = [] { return std::make_unique<test::ProportionalController>(); };
  s.time_limit = 100.0;
  s.nav.place.enabled = true;
  return s;
}

// Corridor 0 served, the place right in most frames, and two key locations: the entry and the
// exit of corridor 0, each near its end of the corridor centre line.
void expect_one_corridor_placed(const RunSummary& sum) {
  EXPECT_EQ(sum.corridors_served, 1);
  ASSERT_TRUE(sum.place.accuracy.has_value());
  EXPECT_GT(*sum.place.accuracy, 0.9);
  ASSERT_EQ(sum.place.keys.size(), 2u);
  EXPECT_EQ(sum.place.keys[0].to, "lane");
  EXPECT_EQ(sum.place.keys[1].to, "headland");
  ASSERT_TRUE(sum.place.key_error_max.has_value());
  EXPECT_LT(*sum.place.key_error_max, 0.5);
}

TEST(PlaceMetrics, OneCorridorInClosedLoopWithTruthLabels) {
  const sim::Field field = build_field(small_vineyard(), ".");
  ClosedLoopSetup s = one_corridor_with_place(field);
  const RunResult r = run_closed_loop(s);
  const RunSummary sum = summarize(r, sim::FieldTruth(field));
  EXPECT_EQ(static_cast<std::size_t>(sum.place.frames), r.frames.size());
  expect_one_corridor_placed(sum);
}

TEST(PlaceMetrics, OneCorridorInClosedLoopWithCameraLabels) {
  // The runner's camera labels (issue 12): the simulated camera every 5th sweep, excess-green
  // boxes, vision::CameraLabeller; the vines drawn in the crop colour the detector knows, as
  // `rownav run --labels camera` does. Measured: accuracy 0.966, the two keys, key error max
  // 0.35 m; the truth labels' bounds hold.
  const sim::Field field = build_field(small_vineyard(), ".");
  ClosedLoopSetup s = one_corridor_with_place(field);
  s.camera_labels = true;
  s.camera.canopy_colour = s.camera.crop_colour;
  const RunResult r = run_closed_loop(s);
  const RunSummary sum = summarize(r, sim::FieldTruth(field));
  expect_one_corridor_placed(sum);
}

}  // namespace
}  // namespace rownav::io
