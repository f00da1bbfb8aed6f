#include "rownav/detect/baseline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/synthetic_rows.hpp"

namespace rownav::detect {
namespace {

DetectorInput input_of(std::vector<Eigen::Vector2f> pts) {
  DetectorInput in;
  in.points = std::move(pts);
  return in;
}

TEST(BaselineDetector, DefaultsAreTheIssueNumbers) {
  const BaselineConfig c;
  EXPECT_EQ(c.x_min, 0.0);
  EXPECT_EQ(c.x_max, 2.5);
  EXPECT_EQ(c.y_max, 0.75);
  EXPECT_EQ(BaselineDetector().name(), "baseline");
}

TEST(BaselineDetector, FindsTwoMaizeRows) {
  test::SyntheticRows s;
  s.rows = 2;
  s.spacing = 0.75;
  s.heading = 0.05;
  s.canopy_half_width = 0.05;
  const auto scene = test::make_rows(s);
  BaselineDetector d;
  const auto obs = d.detect(input_of(scene.points));
  ASSERT_EQ(obs.status, core::DetectionStatus::ok);
  ASSERT_EQ(obs.rows.size(), 2u);
  EXPECT_NEAR(obs.rows[obs.left].offset, scene.truth[1].y_at(0.0), 0.02);
  EXPECT_NEAR(obs.rows[obs.right].offset, scene.truth[0].y_at(0.0), 0.02);
  EXPECT_NEAR(obs.heading, 0.05, 0.01);
  ASSERT_TRUE(obs.corridor);
  EXPECT_NEAR(obs.corridor->width, 0.75, 0.03);
}

TEST(BaselineDetector, FitsYOnXByLeastSquaresNotTls) {
  // y = a x + b by OLS: a = 0.4, b = 0.18 (TLS would give a slope of ~0.78).
  BaselineDetector d;
  const auto obs = d.detect(input_of({{0.0f, 0.1f}, {0.2f, 0.5f}, {0.4f, 0.1f}, {0.6f, 0.5f}}));
  ASSERT_EQ(obs.rows.size(), 1u);
  EXPECT_EQ(obs.status, core::DetectionStatus::degraded);
  EXPECT_NEAR(std::tan(obs.rows[0].heading), 0.4, 1e-5);
  EXPECT_NEAR(obs.rows[0].offset, 0.18, 1e-5);
  EXPECT_EQ(obs.left, 0);
  EXPECT_EQ(obs.right, -1);
}

TEST(BaselineDetector, IgnoresPointsOutsideTheBoxAndInvalidPoints) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<Eigen::Vector2f> pts = {{nan, 0.3f},  {1.0f, nan},  {-0.5f, 0.3f},
                                      {3.0f, 0.3f}, {1.0f, 0.9f}, {1.0f, -2.0f}};
  BaselineDetector d;
  const auto obs = d.detect(input_of(pts));
  EXPECT_EQ(obs.status, core::DetectionStatus::no_rows);
  EXPECT_TRUE(obs.rows.empty());
  EXPECT_EQ(d.detect(input_of({})).status, core::DetectionStatus::no_rows);
}

TEST(BaselineDetector, ValidatesItsConfig) {
  BaselineConfig c;
  c.y_max = 0.0;
  EXPECT_THROW(BaselineDetector{c}, std::invalid_argument);
  c = {};
  c.x_max = c.x_min;
  EXPECT_THROW(BaselineDetector{c}, std::invalid_argument);
}

}  // namespace
}  // namespace rownav::detect
