#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rownav/detect/line_fit.hpp"

namespace rownav::detect {
namespace {

std::vector<Eigen::Vector2f> noisy_line(double slope, double intercept, int n, double sigma,
                                        std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<Eigen::Vector2f> pts;
  for (int i = 0; i < n; ++i) {
    const double x = 0.5 + 4.0 * i / n;
    pts.emplace_back(static_cast<float>(x), static_cast<float>(slope * x + intercept + noise(rng)));
  }
  return pts;
}

TEST(LineFit, TlsRecoversSlopeAndIntercept) {
  const auto pts = noisy_line(0.1, 0.8, 200, 0.02, 1);
  const auto l = fit_line_tls(pts);
  ASSERT_TRUE(l);
  const auto r = make_row_line(*l, pts);
  EXPECT_NEAR(std::tan(r.heading), 0.1, 0.01);
  EXPECT_NEAR(r.offset, 0.8, 0.01);
  EXPECT_NEAR(r.rms, 0.02, 0.005);
  EXPECT_EQ(r.support, 200);
  EXPECT_NEAR(r.x_min, 0.5, 1e-6);
}

TEST(LineFit, DegenerateInputGivesNothing) {
  EXPECT_FALSE(fit_line_tls(std::vector<Eigen::Vector2f>{}));
  EXPECT_FALSE(fit_line_tls(std::vector<Eigen::Vector2f>{{1, 1}}));
  EXPECT_FALSE(fit_line_tls(std::vector<Eigen::Vector2f>{{1, 1}, {1, 1}}));
}

TEST(LineFit, FinalizePicksTheCorridorRows) {
  core::RowObservation obs;
  obs.heading = std::nan("");
  for (const double b : {2.7, -0.9, 0.9, -2.7}) {
    const auto pts = noisy_line(0.05, b, 100, 0.01, 3);
    obs.rows.push_back(make_row_line(*fit_line_tls(pts), pts));
  }
  finalize_observation(obs);
  ASSERT_EQ(obs.rows.size(), 4u);
  EXPECT_LT(obs.rows[0].offset, obs.rows[1].offset);
  ASSERT_EQ(obs.right, 1);
  ASSERT_EQ(obs.left, 2);
  ASSERT_TRUE(obs.corridor);
  EXPECT_NEAR(obs.corridor->offset, 0.0, 0.01);
  EXPECT_NEAR(obs.corridor->heading, std::atan(0.05), 0.005);
  EXPECT_NEAR(obs.corridor->width, 1.8 * std::cos(std::atan(0.05)), 0.02);
  EXPECT_EQ(obs.status, core::DetectionStatus::ok);
  EXPECT_GT(obs.confidence, 0.8);
}

TEST(LineFit, OneSideIsDegradedAndNoneIsNoRows) {
  core::RowObservation obs;
  const auto pts = noisy_line(0.0, 1.0, 50, 0.01, 4);
  obs.rows.push_back(make_row_line(*fit_line_tls(pts), pts));
  finalize_observation(obs);
  EXPECT_EQ(obs.status, core::DetectionStatus::degraded);
  EXPECT_FALSE(obs.corridor);
  EXPECT_LE(obs.confidence, 0.5);
  core::RowObservation empty;
  finalize_observation(empty);
  EXPECT_EQ(empty.status, core::DetectionStatus::no_rows);
  EXPECT_EQ(empty.confidence, 0.0);
}

}  // namespace
}  // namespace rownav::detect

#include "common/synthetic_rows.hpp"

namespace rownav::detect {
namespace {

// The synthetic scene generator the detector tests rely on puts points where its truth says.
TEST(SyntheticRows, PointsLieOnTheirTruthLines) {
  test::SyntheticRows s;
  s.heading = 0.1;
  s.offset = 0.2;
  s.canopy_half_width = 0.0;
  s.noise = 0.0;
  const auto scene = test::make_rows(s);
  ASSERT_EQ(scene.truth.size(), 4u);
  for (const auto& p : scene.points) {
    double best = 1e9;
    for (const auto& l : scene.truth) best = std::min(best, std::abs(l.signed_distance(p.cast<double>())));
    EXPECT_LT(best, 1e-5);
  }
  // offset and spacing are perpendicular to the rows: the intercept at x = 0 is y / cos(heading)
  EXPECT_NEAR(scene.truth[1].y_at(0.0), (0.2 - 0.9) / std::cos(0.1), 1e-9);
  EXPECT_NEAR(scene.truth[2].y_at(0.0), (0.2 + 0.9) / std::cos(0.1), 1e-9);
}

}  // namespace
}  // namespace rownav::detect
