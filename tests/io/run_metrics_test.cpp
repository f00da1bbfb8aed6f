#include "rownav/io/run_metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rownav/sim/field_config.hpp"
#include "rownav/sim/field_truth.hpp"

namespace rownav::io {
namespace {

TEST(RunMetrics, PathLengthRatioOfStraightRunIsOneAndOfSinusoidMore) {
  std::vector<Eigen::Vector2d> ref{{0, 0}, {20, 0}}, straight, wave;
  for (int i = 0; i <= 200; ++i) {
    straight.emplace_back(i * 0.1, 0.0);
    wave.emplace_back(i * 0.1, 0.3 * std::sin(i * 0.1));
  }
  EXPECT_NEAR(*path_length_ratio(straight, ref), 1.0, 1e-9);
  EXPECT_GT(*path_length_ratio(wave, ref), 1.01);
  EXPECT_FALSE(path_length_ratio({{0, 0}, {0.5, 0}}, ref).has_value());
}

// A run along the centre of corridor `k` of `truth` from x0 to x1 (0.05 m steps), in_row.
void drive(RunResult& run, const sim::FieldTruth& truth, int k, double x0, double x1) {
  const double y = truth.corridor_centre(0, k).front().y();
  const double step = x1 > x0 ? 0.05 : -0.05;
  for (double x = x0; step > 0 ? x <= x1 : x >= x1; x += step) {
    RunSample s;
    s.T_world_base = core::Pose2(x, y, step > 0 ? 0.0 : std::numbers::pi);
    const auto gt = truth.at(s.T_world_base, 0.0, 0.0);
    s.place = gt.place, s.corridor = gt.corridor;
    run.samples.push_back(s);
  }
}

TEST(RunMetrics, ACorridorLeftHalfWayIsNotServed) {
  sim::FieldConfig f;
  f.vineyard.rows = 4, f.vineyard.row_length = 12.0, f.vineyard.row_spacing = 2.0;
  const sim::Field field = sim::generate_field(f);
  const sim::FieldTruth truth(field);
  RunResult run;
  run.order = {0, 1, 2};
  run.served = 3;  // what the navigator claims
  run.final_state = navigate::NavState::done;
  drive(run, truth, 0, -1.5, 13.5);
  drive(run, truth, 1, 13.5, -1.5);
  drive(run, truth, 2, -1.5, 5.0);  // a false row end 5 m in
  RunSummary s = summarize(run, truth);
  EXPECT_EQ(s.corridors_served, 2);
  EXPECT_TRUE(s.corridors_in_order);  // 0, 1 is a prefix of the plan
  EXPECT_FALSE(s.success);
  run.samples.clear();
  drive(run, truth, 0, -1.5, 13.5);
  drive(run, truth, 1, 13.5, -1.5);
  drive(run, truth, 2, -1.5, 13.5);
  s = summarize(run, truth);
  EXPECT_EQ(s.corridors_served, 3);
  EXPECT_TRUE(s.success);
}

/// Three rows 12 m long and 2 m apart; row `i`, its direction and its left normal.
struct ThreeRows {
  explicit ThreeRows(std::size_t i)
      : field(make()),
        truth(field),
        row(field.rows[i]),
        along((row.end() - row.start()).normalized()),
        across(-along.y(), along.x()) {}
  static sim::Field make() {
    sim::FieldConfig f;
    f.vineyard.rows = 3, f.vineyard.row_length = 12.0, f.vineyard.row_spacing = 2.0;
    return sim::generate_field(f);
  }
  const sim::Field field;
  const sim::FieldTruth truth;
  const sim::Row& row;
  const Eigen::Vector2d along, across;
};

TEST(RunMetrics, RowEndsPastTheLastPlantAreAPositiveOffsetAlongTheRowAndShortOnesNegative) {
  const ThreeRows f(1);
  const auto& [field, truth, row, along, across] = f;
  RunResult run;
  // 0.3 m past the far end (and 0.1 m beside it); 0.1 m short of the near end.
  run.row_ends_world = {row.end() + 0.3 * along + 0.1 * across, row.start() + 0.1 * along};
  const RunSummary s = summarize(run, truth);
  ASSERT_TRUE(s.row_end_along_mean.has_value());
  EXPECT_NEAR(*s.row_end_along_mean, 0.5 * (0.3 - 0.1), 1e-9);
  EXPECT_NEAR(*s.row_end_error_max, std::hypot(0.3, 0.1), 1e-9);
  // Each end on its own (row_ends.csv): matched to its true end, split along and across the row
  // (+ left looking out of the row: at the far end that is the row's own left).
  ASSERT_EQ(s.row_ends.size(), 2u);
  EXPECT_LT((s.row_ends[0].truth - row.end()).norm(), 1e-9);
  EXPECT_NEAR(s.row_ends[0].along, 0.3, 1e-9);
  EXPECT_NEAR(s.row_ends[0].across, 0.1, 1e-9);
  EXPECT_LT((s.row_ends[1].truth - row.start()).norm(), 1e-9);
  EXPECT_NEAR(s.row_ends[1].along, -0.1, 1e-9);
  EXPECT_NEAR(s.row_ends[1].across, 0.0, 1e-9);
  EXPECT_NEAR(s.row_ends[1].error, 0.1, 1e-9);
  run.row_ends_world = {row.end() - 0.2 * along};
  EXPECT_NEAR(*summarize(run, truth).row_end_along_mean, -0.2, 1e-9);
}

TEST(RunMetrics, EachPoleIsScoredAgainstTheFramesNearestEndPointAndFarPointsOnlyCounted) {
  // Bertoglio 2023 Table II: in each turn frame, each true pole against the nearest end point.
  // A point farther than half the spacing (2 m) from every row end is a bush: only counted.
  const ThreeRows f(2);
  const auto& [field, truth, row, along, across] = f;
  RunResult run;
  // Frame 1: the end seen 0.1 m beside it, and a vine 0.8 m into the row (not the nearest);
  // frame 2: 0.3 m past it, the start 0.05 m short, and a bush 3 m out in the headland.
  for (const auto& [t, p] :
       std::vector<std::pair<double, Eigen::Vector2d>>{{1.0, row.end() + 0.1 * across},
                                                       {1.0, row.end() - 0.8 * along},
                                                       {2.0, row.end() + 0.3 * along},
                                                       {2.0, row.start() - 0.05 * along},
                                                       {2.0, row.end() + 3.0 * along}})
    run.turn_row_ends_world.push_back({t, p});
  const RunSummary s = summarize(run, truth);
  EXPECT_EQ(s.turn_row_end_points, 3);
  EXPECT_EQ(s.turn_row_end_spurious, 1);
  EXPECT_NEAR(*s.turn_row_end_error_mean, (0.1 + 0.3 + 0.05) / 3.0, 1e-9);
  EXPECT_NEAR(*s.turn_row_end_error_max, 0.3, 1e-9);
  EXPECT_NEAR(*s.turn_row_end_error_min, 0.05, 1e-9);
  EXPECT_FALSE(summarize(RunResult{}, truth).turn_row_end_error_mean.has_value());
}

}  // namespace
}  // namespace rownav::io
