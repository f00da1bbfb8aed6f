// The nearest-row check (detect/nearest_row.hpp) on hand-made 2D scans with known rows.
#include "rownav/detect/nearest_row.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "rownav/detect/line_fit.hpp"

namespace rownav::detect {
namespace {

void add_row(std::vector<Eigen::Vector2f>& pts, double y, double x0, double x1, int n,
             std::mt19937_64& rng) {
  std::normal_distribution<double> noise(0.0, 0.03);
  for (int i = 0; i < n; ++i) {
    const double x = x0 + (x1 - x0) * i / std::max(1, n - 1);
    pts.emplace_back(float(x), float(y + noise(rng)));
  }
}

// Returns of the right row (-0.85), the far left row (+2.55), and a near-left band at +0.85
// from x0 to x1 with n returns; seeded.
std::vector<Eigen::Vector2f> scan_with_near_band(double x0, double x1, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Eigen::Vector2f> pts;
  add_row(pts, -0.85, -1.0, 9.0, 30, rng);
  add_row(pts, 2.55, -1.0, 9.0, 30, rng);
  add_row(pts, 0.85, x0, x1, n, rng);
  return pts;
}

// A detector's answer that skipped the near left row: right row at -0.85, "left" at +2.55
// (the row one spacing of 1.7 m out); the true near row stands at +0.85.
core::RowObservation skipped_left(const std::vector<Eigen::Vector2f>& pts) {
  core::RowObservation obs;
  obs.heading = 0.0;
  std::vector<Eigen::Vector2f> r, l;
  for (const auto& p : pts)
    if (std::abs(p.y() + 0.85f) < 0.2f)
      r.push_back(p);
    else if (std::abs(p.y() - 2.55f) < 0.2f)
      l.push_back(p);
  obs.rows.push_back(make_row_line(*fit_line_tls(r), r));
  obs.rows.push_back(make_row_line(*fit_line_tls(l), l));
  finalize_observation(obs);
  return obs;
}

TEST(NearestRow, ALongRowFirstSeenAheadIsSteppedInto) {
  // Under a thin canopy the near row's returns can start metres ahead (beams beside the robot
  // pass through its gaps): from 3 m to the 9 m range, it is the row that hides the far one.
  const auto pts = scan_with_near_band(3.0, 9.0, 10, 1);
  auto obs = skipped_left(pts);
  ASSERT_NEAR(obs.rows[std::size_t(obs.left)].offset, 2.55, 0.05);
  EXPECT_EQ(step_in_nearest_rows(obs, pts, NearestRowConfig{}, false), 1);
  EXPECT_NEAR(obs.rows[std::size_t(obs.left)].offset, 0.85, 0.05);
  ASSERT_TRUE(obs.corridor);
  EXPECT_NEAR(obs.corridor->offset, 0.0, 0.05);
}

TEST(NearestRow, AShortPieceFarAheadIsNoRow) {
  // Six returns over 1.5 m from 6 m ahead (a weed clump, the scan plane touching a bump) pass
  // the support, length and direction tests but start farther ahead than their length allows.
  const auto pts = scan_with_near_band(6.0, 7.5, 6, 2);
  auto obs = skipped_left(pts);
  EXPECT_EQ(step_in_nearest_rows(obs, pts, NearestRowConfig{}, false), 0);
  EXPECT_NEAR(obs.rows[std::size_t(obs.left)].offset, 2.55, 0.05);
  // Without the start rule the same piece is taken for the row.
  NearestRowConfig no_start;
  no_start.min_length_per_start = 0.0;
  EXPECT_EQ(step_in_nearest_rows(obs, pts, no_start, false), 1);
}

TEST(NearestRow, ANegativeLengthPerStartIsRefusedByName) {
  NearestRowConfig c;
  c.min_length_per_start = -0.1;
  EXPECT_THROW(
      {
        try {
          c.validate();
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("min_length_per_start"), std::string::npos);
          throw;
        }
      },
      std::invalid_argument);
}

}  // namespace
}  // namespace rownav::detect
