#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

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

// Parallel rows along `heading` (rad) at the given offsets across, plus a line crossing the
// corridor at `cross_deg` to the rows whose nearest point lies `cross_offset` left of the robot.
core::RowObservation rows_and_a_crossing_line(double heading, const std::vector<double>& offsets,
                                             double cross_deg, double cross_offset,
                                             std::uint64_t seed) {
  core::RowObservation obs;
  obs.heading = std::nan("");
  for (const double b : offsets) {
    const auto pts = noisy_line(std::tan(heading), b / std::cos(heading), 60, 0.02, seed++);
    obs.rows.push_back(make_row_line(*fit_line_tls(pts), pts));
  }
  // The crossing line's points start 3 m ahead, as the scan plane meets the ground there.
  const double a = heading + cross_deg * std::numbers::pi / 180.0;
  std::vector<Eigen::Vector2f> pts;
  for (int i = 0; i < 30; ++i) {
    const double x = 3.0 + 0.1 * i;
    pts.emplace_back(float(x), float(cross_offset + std::tan(a) * x));
  }
  auto cross = make_row_line(*fit_line_tls(pts), pts);
  obs.rows.push_back(cross);
  return obs;
}

TEST(LineFit, ALineCrossingTheCorridorIsNotACorridorRow) {
  // Random corridors (seeded): robot yawed up to 10 deg, spacing 1.5-3 m, off-centre up to 0.3 m;
  // the nearest line on the left crosses the rows at 30-60 deg. The corridor is the parallel
  // pair around the robot.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> yaw(-0.17, 0.17), spacing(1.5, 3.0), off(-0.3, 0.3),
      cross(30.0, 60.0);
  for (int k = 0; k < 50; ++k) {
    SCOPED_TRACE(k);
    const double h = yaw(rng), s = spacing(rng), o = off(rng);
    const double right = -0.5 * s + o, left = 0.5 * s + o;
    auto obs = rows_and_a_crossing_line(h, {right - s, right, left, left + s}, cross(rng),
                                        0.25 * left, 100 + 10 * std::uint64_t(k));
    finalize_observation(obs);
    ASSERT_TRUE(obs.corridor);
    EXPECT_NEAR(obs.corridor->offset, o / std::cos(h), 0.05);
    EXPECT_NEAR(obs.corridor->width, s, 0.05);
    EXPECT_NEAR(obs.corridor->heading, h, 0.03);
  }
}

TEST(LineFit, ACrossingLineWithNoParallelRowOnItsSideLeavesOneSide) {
  auto obs = rows_and_a_crossing_line(0.05, {-2.7, -0.9}, 45.0, 0.3, 7);
  finalize_observation(obs);
  EXPECT_FALSE(obs.corridor);
  EXPECT_EQ(obs.status, core::DetectionStatus::degraded);
  ASSERT_GE(obs.right, 0);
  EXPECT_NEAR(obs.rows[std::size_t(obs.right)].offset, -0.9, 0.05);
  EXPECT_EQ(obs.left, -1);
}

TEST(LineFit, NinetyDegreesOfSkewPairsAnyTwoLinesAsPublishedBaselinesDo) {
  auto obs = rows_and_a_crossing_line(0.05, {-0.9, 2.7}, 45.0, 0.3, 8);
  finalize_observation(obs, 0.0, CorridorPairConfig{.max_skew_deg = 90.0});
  ASSERT_TRUE(obs.corridor);
  EXPECT_NEAR(obs.rows[std::size_t(obs.left)].offset, 0.3, 0.05);  // the crossing line
}

TEST(LineFit, RowsWithinTheSkewLimitStayPaired) {
  // 12 deg apart (a short row's fit on a yawed robot): still one corridor, both sides kept.
  core::RowObservation obs;
  obs.heading = std::nan("");
  for (const auto& [slope, b] : {std::pair{0.0, -0.9}, std::pair{std::tan(0.21), 0.9}}) {
    const auto pts = noisy_line(slope, b, 40, 0.01, 9);
    obs.rows.push_back(make_row_line(*fit_line_tls(pts), pts));
  }
  finalize_observation(obs);
  EXPECT_TRUE(obs.corridor);
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
