#include "rownav/detect/parallel_lines.hpp"

#include <gtest/gtest.h>


#include "detector_eval.hpp"

namespace rownav::detect {
namespace {

using test::kDeg;

TEST(ParallelLines, SyntheticSweepCleanish) {
  ParallelLinesDetector det;
  test::sweep_cleanish(det, "parallel_lines", 2);
}

TEST(ParallelLines, SyntheticHard) {
  ParallelLinesDetector det;
  // Weed strips at this density look like rows of their own to a LiDAR: some scenes are lost.
  EXPECT_GE(test::sweep_hard(det, "parallel_lines"), 8);  // measured 8 / 12: RANSAC still pairs a row with a weed strip at times
}

TEST(ParallelLines, OneRowIsDegraded) {
  ParallelLinesDetector det;
  test::SyntheticRows s;
  s.rows = 1, s.offset = 0.9;
  auto obs = det.detect(test::input_of(test::make_rows(s)));
  EXPECT_NE(obs.status, core::DetectionStatus::ok);
}

TEST(ParallelLines, RobotOffCentre) {
  ParallelLinesDetector det;
  for (const double off : {-0.6, 0.6}) {
    test::SyntheticRows s;
    s.rows = 4, s.spacing = 1.8, s.offset = off, s.heading = -8 * kDeg, s.weeds = 50;
    const auto scene = test::make_rows(s);
    const auto obs = det.detect(test::input_of(scene));
    const auto e = test::corridor_error(obs, scene.truth);
    ASSERT_TRUE(e.found);
    EXPECT_LT(e.worst(), 0.03);
  }
}

TEST(ParallelLines, DegenerateInputs) {
  ParallelLinesDetector det;
  int i = 0;
  for (const auto& pts : test::degenerate_frames()) {
    DetectorInput in;
    in.points = pts;
    const auto obs = det.detect(in);
    SCOPED_TRACE(i++);
    EXPECT_NE(obs.status, core::DetectionStatus::ok);
    EXPECT_FALSE(det.last_trunks()[0].found);
  }
}

TEST(ParallelLines, DeterministicAndSeeded) {
  test::SyntheticRows s;
  s.weeds = 300, s.outliers = 200, s.heading = 0.1, s.noise = 0.03;
  const auto in = test::input_of(test::make_rows(s));
  ParallelLinesDetector a, b;
  const auto oa = a.detect(in), ob = b.detect(in), oa2 = a.detect(in);
  ASSERT_EQ(oa.rows.size(), ob.rows.size());
  EXPECT_EQ(oa.heading, ob.heading);
  EXPECT_EQ(oa.heading, oa2.heading);
}

TEST(ParallelLines, ConfigValidation) {
  ParallelLinesConfig c;
  c.max_width = 0.1;
  EXPECT_THROW(ParallelLinesDetector{c}, std::invalid_argument);
  c = {};
  c.trunk_z_max = 0.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

TEST(ParallelLines, SimulatedVineyardFrameAndTrunks) {
  sim::FieldConfig fc;
  fc.vineyard.rows = 6, fc.vineyard.row_spacing = 1.8, fc.vineyard.row_length = 30.0;
  const auto field = sim::generate_field(fc);
  preprocess::PreprocessConfig pc;
  pc.height.min_height = 0.1;  // keep the trunk band (Lan 2022 Fig. 1)
  preprocess::Preprocessor pre(pc);
  ParallelLinesDetector det;
  int trunks_right = 0;
  for (const double dh : {-5.0, 5.0}) {
    const auto f = test::sim_frame(field, 2, dh * kDeg, 0.2);
    pre.run(f.cloud_base);
    const auto obs = det.detect(pre.input(0.0));
    const auto e = test::expect_sim_frame_accuracy("parallel_lines", dh, obs, f.truth);
    ASSERT_TRUE(e.found);
    // Trunks: each found centre is near a vine or post of the field (base frame).
    const core::Pose2 T = f.truth.T_world_base;
    for (int side = 0; side < 2; ++side) {
      const auto& t = det.last_trunks()[std::size_t(side)];
      EXPECT_EQ(side == 0, t.centre.y() > 0.0);
      if (!t.found) continue;
      double nearest = 1e9;
      for (const auto& p : field.plants) nearest = std::min(nearest, (T * t.centre - p.position).norm());
      std::printf("  trunk %s at (%.2f, %.2f), %.1f cm from the nearest plant\n",
                  side == 0 ? "left" : "right", t.centre.x(), t.centre.y(), 100 * nearest);
      trunks_right += nearest < 0.1;
    }
  }
  // Measured: 3 of the 4 nearest trunks within 3 cm; the 4th is low canopy between two vines.
  EXPECT_GE(trunks_right, 3);
}

TEST(ParallelLines, RealCornRows) {
  const auto s = test::corn_stats(std::make_unique<ParallelLinesDetector>(ParallelLinesConfig::row_crop())).eval;
  ASSERT_EQ(s.frames, 1630);
  EXPECT_GE(s.output_rate, 0.98);
  EXPECT_LT(s.lateral_05_m.median, 0.05);  // trivial baseline 7.8 cm
  EXPECT_LT(s.row_heading_deg.median, 4.0);  // trivial baseline 8.6 deg
}

}  // namespace
}  // namespace rownav::detect
