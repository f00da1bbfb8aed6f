// The rows' sharpest projection direction (detect/row_direction.hpp) on synthetic 2D scans with
// known rows: random spacings, headings, offsets, gaps and clutter (seeded).
#include "rownav/detect/row_direction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "rownav/detect/line_fit.hpp"

namespace rownav::detect {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A scan of `rows` parallel rows `spacing` apart, heading `heading` in the robot frame, the robot
// `offset` left of the corridor centre; each return kept with probability `fill` (gaps, a sparse
// canopy), plus `clutter` uniform returns (weeds) within 6 m.
std::vector<Eigen::Vector2f> scan(double heading, double spacing, double offset, double fill,
                                  int clutter, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.05);
  const Eigen::Vector2d d(std::cos(heading), std::sin(heading)), n(-d.y(), d.x());
  std::vector<Eigen::Vector2f> pts;
  for (int k = -2; k <= 2; ++k) {
    const double across = (k + (k > 0 ? -0.5 : 0.5) * (k != 0)) * spacing - offset;
    if (k == 0) continue;  // the corridor itself
    for (double t = -2.0; t <= 8.0; t += 0.05)
      if (u(rng) < fill) pts.push_back((t * d + (across + noise(rng)) * n).cast<float>());
  }
  for (int i = 0; i < clutter; ++i)
    pts.emplace_back(float(-1.0 + 7.0 * u(rng)), float(-3.0 + 6.0 * u(rng)));
  return pts;
}

TEST(RowDirection, RecoversTheRowsHeadingOnRandomCorridorsWithGapsAndClutter) {
  std::mt19937_64 rng(1107);
  std::uniform_real_distribution<double> heading(-25.0, 25.0), spacing(1.2, 3.5), offset(-0.3, 0.3),
      fill(0.15, 1.0);
  const RowDirectionConfig c;
  int worst_failures = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double h = heading(rng) * kDeg, s = spacing(rng);
    const auto pts = scan(h, s, offset(rng) * s, fill(rng), 40, rng);
    const auto found = row_direction(pts, c);
    ASSERT_TRUE(found.has_value()) << "trial " << trial;
    if (std::abs(*found - h) > 1.0 * kDeg) ++worst_failures;
  }
  EXPECT_EQ(worst_failures, 0);  // within 1 deg on every corridor
}

TEST(RowDirection, ClutterWithoutRowsHasNoSharpDirection) {
  std::mt19937_64 rng(11);
  int found = 0;
  for (int trial = 0; trial < 50; ++trial)
    found += row_direction(scan(0.0, 2.0, 0.0, 0.0, 300, rng), {}).has_value();
  EXPECT_LE(found, 2);  // a random heap of weeds is (almost) never a direction
}

TEST(RowDirection, RowsOutsideTheSearchedArcGiveNoHeadingNotTheArcsEdge) {
  std::mt19937_64 rng(12);
  RowDirectionConfig c;
  c.max_angle_deg = 20.0;
  EXPECT_FALSE(row_direction(scan(35.0 * kDeg, 2.0, 0.0, 1.0, 0, rng), c).has_value());
  EXPECT_TRUE(row_direction(scan(15.0 * kDeg, 2.0, 0.0, 1.0, 0, rng), c).has_value());
}

TEST(RowDirection, NonFinitePointsAreSkippedAndTooFewGiveNothing) {
  std::mt19937_64 rng(13);
  auto pts = scan(5.0 * kDeg, 1.8, 0.0, 1.0, 0, rng);
  const auto clean = row_direction(pts, {});
  pts.emplace_back(std::numeric_limits<float>::quiet_NaN(), 1.0f);
  pts.emplace_back(std::numeric_limits<float>::infinity(), 0.0f);
  const auto with_nan = row_direction(pts, {});
  ASSERT_TRUE(clean && with_nan);
  EXPECT_DOUBLE_EQ(*clean, *with_nan);
  EXPECT_FALSE(row_direction(std::vector<Eigen::Vector2f>(5, Eigen::Vector2f(1, 1)), {}));
  RowDirectionConfig off;
  off.enabled = false;
  EXPECT_FALSE(row_direction(pts, off));
}

TEST(RowDirection, ARowFittedOffTheRowsHeadingIsDroppedAndTheCorridorPickedAgain) {
  std::mt19937_64 rng(14);
  const auto pts = scan(0.0, 1.7, 0.0, 1.0, 0, rng);  // rows at +-0.85, +-2.55
  core::RowObservation obs;
  obs.heading = std::numeric_limits<double>::quiet_NaN();
  auto row = [](double y0, double deg) {
    const double a = deg * kDeg;
    const std::vector<Eigen::Vector2f> support{
        Eigen::Vector2f(0.0f, float(y0)),
        Eigen::Vector2f(float(4.0 * std::cos(a)), float(y0 + 4.0 * std::sin(a)))};
    return make_row_line(
        core::Line2(Eigen::Vector2d(0.0, y0), Eigen::Vector2d(std::cos(a), std::sin(a))), support);
  };
  // A short fit 9 deg off crossing x = 0 at +0.35 (the near left row plus the row behind),
  // the true near left row at +0.85, the right row at -0.85.
  obs.rows = {row(-0.85, 0.0), row(0.35, 9.0), row(0.85, 0.5)};
  finalize_observation(obs);
  ASSERT_NEAR(obs.rows[std::size_t(obs.left)].offset, 0.35, 1e-9);
  EXPECT_EQ(keep_rows_along_direction(obs, pts, {}), 1);
  ASSERT_EQ(obs.rows.size(), 2u);
  EXPECT_NEAR(obs.rows[std::size_t(obs.left)].offset, 0.85, 1e-9);
  ASSERT_TRUE(obs.corridor.has_value());
  EXPECT_NEAR(obs.corridor->offset, 0.0, 1e-6);
}

TEST(RowDirectionConfig, ValidateNamesTheField) {
  auto msg = [](RowDirectionConfig c) {
    try {
      c.validate();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  RowDirectionConfig c;
  EXPECT_EQ(msg(c), "");
  c.bin = 0.0;
  EXPECT_NE(msg(c).find("bin"), std::string::npos);
  c = {};
  c.min_contrast = 0.5;
  EXPECT_NE(msg(c).find("min_contrast"), std::string::npos);
  c = {};
  c.max_row_skew_deg = 0.0;
  EXPECT_NE(msg(c).find("max_row_skew_deg"), std::string::npos);
}

}  // namespace
}  // namespace rownav::detect
