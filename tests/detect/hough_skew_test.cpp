#include "rownav/detect/hough_skew.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

#include "detector_eval.hpp"

namespace rownav::detect {
namespace {

using test::kDeg;

// Sweep: headings -15..15 deg, three spacings, off-centre robot, canopy 0.3 m, noise, gaps,
// weeds and outliers. "Clean-ish": the accuracy bounds of the brief.
TEST(HoughSkew, SyntheticSweepCleanish) {
  HoughSkewDetector det;
  test::sweep_cleanish(det, "hough_skew");
}

TEST(HoughSkew, SyntheticHard) {
  HoughSkewDetector det;
  // Weed strips at this density look like rows of their own to a LiDAR: some scenes are lost.
  EXPECT_GE(test::sweep_hard(det, "hough_skew"), 8);  // measured 8 / 12
}

TEST(HoughSkew, AnyNumberOfRows) {
  HoughSkewDetector det;
  for (int rows = 1; rows <= 8; ++rows) {
    test::SyntheticRows s;
    s.rows = rows, s.spacing = 0.9, s.heading = 6 * kDeg, s.offset = 0.3, s.weeds = 20;
    const auto scene = test::make_rows(s);
    const auto obs = det.detect(test::input_of(scene));
    SCOPED_TRACE(rows);
    EXPECT_EQ(static_cast<int>(obs.rows.size()), rows);
    EXPECT_EQ(obs.status, rows == 1 ? core::DetectionStatus::degraded : core::DetectionStatus::ok);
    for (std::size_t k = 0; k < obs.rows.size() && obs.rows.size() == scene.truth.size(); ++k)
      EXPECT_NEAR(obs.rows[k].line.y_at(2.0), scene.truth[k].y_at(2.0), 0.03);
  }
}

TEST(HoughSkew, RobotOffCentre) {
  HoughSkewDetector det;
  for (const double off : {-0.6, 0.6}) {
    test::SyntheticRows s;
    s.rows = 4, s.spacing = 1.8, s.offset = off, s.heading = -8 * kDeg, s.weeds = 50;
    const auto scene = test::make_rows(s);
    const auto obs = det.detect(test::input_of(scene));
    const auto e = test::corridor_error(obs, scene.truth);
    ASSERT_TRUE(e.found);
    EXPECT_LT(e.worst(), 0.03);
    ASSERT_TRUE(obs.corridor);
    EXPECT_NEAR(obs.corridor->offset, off / std::cos(8 * kDeg), 0.03);
  }
}

TEST(HoughSkew, DegenerateInputs) {
  HoughSkewDetector det;
  int i = 0;
  for (const auto& pts : test::degenerate_frames()) {
    DetectorInput in;
    in.points = pts;
    const auto obs = det.detect(in);
    if (std::getenv("ROWNAV_DEBUG"))
      for (const auto& r : obs.rows)
        std::printf("frame %d: row %.3f h %.2f support %d x %.2f..%.2f rms %.3f\n", i, r.offset,
                    r.heading, r.support, r.x_min, r.x_max, r.rms);
    SCOPED_TRACE(i++);
    EXPECT_NE(obs.status, core::DetectionStatus::ok);
  }
}

TEST(HoughSkew, Deterministic) {
  test::SyntheticRows s;
  s.weeds = 200, s.outliers = 100, s.heading = 0.1;
  const auto in = test::input_of(test::make_rows(s));
  HoughSkewDetector a, b;
  const auto oa = a.detect(in), ob = b.detect(in), oa2 = a.detect(in);
  ASSERT_EQ(oa.rows.size(), ob.rows.size());
  EXPECT_EQ(oa.heading, ob.heading);
  EXPECT_EQ(oa.heading, oa2.heading);
  for (std::size_t k = 0; k < oa.rows.size(); ++k) EXPECT_EQ(oa.rows[k].offset, ob.rows[k].offset);
}

TEST(HoughSkew, PaperModeIsCoarser) {
  // Without the rownav refinements the answer is the paper's (1 deg columns, 8 cm bins).
  HoughSkewConfig c;
  c.refine_heading = false, c.refine_rows = false;
  HoughSkewDetector det(c);
  test::SyntheticRows s;
  s.heading = 4.4 * kDeg, s.weeds = 30;
  const auto scene = test::make_rows(s);
  const auto e = test::corridor_error(det.detect(test::input_of(scene)), scene.truth);
  ASSERT_TRUE(e.found);
  EXPECT_LT(e.heading_deg, 1.0);
  EXPECT_LT(e.worst(), 0.12);
}

TEST(HoughSkew, ConfigValidation) {
  HoughSkewConfig c;
  c.bins = 1;
  EXPECT_THROW(HoughSkewDetector{c}, std::invalid_argument);
  c = {};
  c.y_min = 5.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

TEST(HoughSkew, SimulatedVineyardFrame) {
  sim::FieldConfig fc;
  fc.vineyard.rows = 6, fc.vineyard.row_spacing = 1.8, fc.vineyard.row_length = 30.0;
  const auto field = sim::generate_field(fc);
  preprocess::Preprocessor pre;
  HoughSkewDetector det;
  for (const double dh : {-5.0, 5.0}) {
    const auto f = test::sim_frame(field, 2, dh * kDeg, 0.2);
    pre.run(f.cloud_base);
    const auto obs = det.detect(pre.input(0.0));
    const auto e = test::expect_sim_frame_accuracy("hough_skew", dh, obs, f.truth);
    ASSERT_TRUE(e.found);
  }
}

TEST(HoughSkew, RealCornRows) {
  const auto s = test::corn_stats(std::make_unique<HoughSkewDetector>(HoughSkewConfig::row_crop())).eval;
  ASSERT_EQ(s.frames, 1630);
  EXPECT_GE(s.output_rate, 0.98);
  EXPECT_LT(s.lateral_05_m.median, 0.05);  // trivial baseline 7.8 cm
  EXPECT_LT(s.row_heading_deg.median, 4.0);  // trivial baseline 8.6 deg
}

}  // namespace
}  // namespace rownav::detect
