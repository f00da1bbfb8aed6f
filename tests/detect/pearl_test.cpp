#include "rownav/detect/pearl.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include "../common/synthetic_rows.hpp"
#include "detector_eval.hpp"
#include "rownav/detect/ransac_lines.hpp"

namespace rownav::detect {
namespace {

using test::make_rows;
using test::SyntheticRows;

PearlConfig variant(PearlVariant v, std::uint64_t seed = 1) {
  PearlConfig c;
  c.variant = v;
  c.seed = seed;
  return c;
}

DetectorInput input_of(const std::vector<Eigen::Vector2f>& pts) {
  DetectorInput in;
  in.points = pts;
  return in;
}

TEST(Pearl, NamesFollowTheVariant) {
  EXPECT_EQ(PearlDetector(variant(PearlVariant::pearl)).name(), "pearl");
  EXPECT_EQ(PearlDetector(variant(PearlVariant::opal)).name(), "opal");
  EXPECT_EQ(PearlDetector(variant(PearlVariant::ruby)).name(), "ruby");
  PearlConfig bad;
  bad.zeta = 0.0;
  EXPECT_THROW(PearlDetector{bad}, std::invalid_argument);
  int fields = 0;
  PearlConfig c;
  auto count = [&](std::string_view, auto&) { ++fields; };
  PearlConfig::fields(c, count);
  EXPECT_EQ(fields, 28);  // + nearest_row, planar_label_cost, row_direction (issue 11)
  PearlVariant v{};
  EXPECT_TRUE(core::enum_from_name("opal", v));
  EXPECT_EQ(v, PearlVariant::opal);
  RansacLinesConfig r;
  r.min_inliers = 1;
  EXPECT_THROW(RansacLinesDetector{r}, std::invalid_argument);
}

// Narrow canopy (+-5 cm): < 1 deg and < 3 cm; wide canopy (+-15 cm, points spread uniformly
// across 30 cm): < 1 deg and < 5 cm at x = 1 m (measured worst 4.3 cm: the edge points the
// outlier threshold drops are not symmetric).
TEST(Pearl, RubyFindsCleanCorridorRows) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const bool wide = seed > 10;
    SyntheticRows s;
    s.canopy_half_width = wide ? 0.15 : 0.05;
    s.seed = seed;
    s.heading = 0.05 * static_cast<double>(seed % 5) - 0.1;
    s.offset = 0.1 * static_cast<double>(seed % 3) - 0.1;
    const auto scene = make_rows(s);
    PearlDetector det(variant(PearlVariant::ruby, seed));
    const auto obs = det.detect(input_of(scene.points));
    const auto sc = test::score_corridor(obs, scene.truth, 1.0);
    EXPECT_EQ(obs.status, core::DetectionStatus::ok);
    EXPECT_EQ(sc.found, 2);
    EXPECT_LT(sc.heading_deg, 1.0);
    EXPECT_LT(sc.lateral, wide ? 0.05 : 0.03) << "seed " << seed;
  }
}

// Share of 20 scenes where both corridor rows are found within 2 deg and 5 cm at x = 1 m.
double robustness(const PearlConfig& base, int weeds, int outliers, double* worst_lateral) {
  int good = 0;
  *worst_lateral = 0.0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    SyntheticRows s;
    s.seed = seed;
    s.heading = 0.02 * static_cast<double>(seed % 7) - 0.06;
    s.weeds = weeds;
    s.outliers = outliers;
    s.gap_probability = 0.1;
    const auto scene = make_rows(s);
    PearlConfig c = base;
    c.seed = seed;
    PearlDetector det(c);
    const auto sc = test::score_corridor(det.detect(input_of(scene.points)), scene.truth, 1.0);
    const bool ok = sc.found == 2 && sc.heading_deg < 2.0 && sc.lateral < 0.05;
    good += ok ? 1 : 0;
    if (sc.found == 2) *worst_lateral = std::max(*worst_lateral, sc.lateral);
  }
  return good / 20.0;
}

// Malavazi 2018 sec. 3: three weed levels (none, some, a lot). Measured here on synthetic rows
// with gaps: 0 / 80 / 250 weed points in the corridors' middle third (620 row points) + outliers.
TEST(Pearl, WeedLevelsRobustnessOfTheThreeVariants) {
  const std::array<std::pair<int, int>, 3> levels{{{0, 0}, {80, 10}, {250, 30}}};
  std::array<std::array<double, 3>, 3> r{};
  for (std::size_t l = 0; l < 3; ++l)
    for (const auto v : {PearlVariant::pearl, PearlVariant::opal, PearlVariant::ruby}) {
      double worst = 0.0;
      const auto vi = static_cast<std::size_t>(v);
      r[l][vi] = robustness(variant(v), levels[l].first, levels[l].second, &worst);
      std::printf("level %zu (%d weeds, %d outliers) %-5s success %.2f worst lateral %.3f m\n",
                  l + 1, levels[l].first, levels[l].second, std::string(core::enum_name(v)).c_str(),
                  r[l][vi], worst);
    }
  // Measured (seeds 1..20): level 1 pearl 1.00 opal 1.00 ruby 1.00; level 2 0.85 / 0.75 / 0.85;
  // level 3 0.50 / 0.40 / 0.60. 250 weeds in the corridors' middle third form a weed "row" that
  // every variant sometimes takes for a crop row. RUBY >= PEARL and RUBY >= OPAL hold on every
  // level; OPAL >= PEARL does not (levels 2, 3): the paper's ordering is only partly reproduced.
  EXPECT_GE(r[0][2], 0.95);  // ruby, clean
  EXPECT_GE(r[1][2], 0.8);   // ruby, some weeds
  EXPECT_GE(r[2][2], 0.5);   // ruby, many weeds
  for (std::size_t l = 0; l < 3; ++l) {
    EXPECT_GE(r[l][2] + 1e-9, r[l][1]) << "level " << l + 1;
    EXPECT_GE(r[l][2] + 1e-9, r[l][0]) << "level " << l + 1;
  }
}

TEST(Pearl, DegenerateInputsGiveNoRowsOrDegraded) {
  PearlDetector det(variant(PearlVariant::ruby));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const auto status_of = [&](const std::vector<Eigen::Vector2f>& pts) {
    return det.detect(input_of(pts)).status;
  };
  EXPECT_EQ(status_of({}), core::DetectionStatus::no_rows);
  EXPECT_EQ(status_of({{1.0f, 1.0f}}), core::DetectionStatus::no_rows);
  EXPECT_EQ(status_of(std::vector<Eigen::Vector2f>(50, {nan, 1.0f})),
            core::DetectionStatus::no_rows);
  EXPECT_EQ(status_of(std::vector<Eigen::Vector2f>(50, {2.0f, 1.0f})),
            core::DetectionStatus::no_rows);
  std::vector<Eigen::Vector2f> wall, side, open;
  for (int i = 0; i < 200; ++i) wall.emplace_back(3.0f, -2.0f + 0.02f * static_cast<float>(i));
  EXPECT_EQ(status_of(wall), core::DetectionStatus::no_rows);  // across the robot: not a row
  for (int i = 0; i < 200; ++i) side.emplace_back(0.3f + 0.03f * static_cast<float>(i), 0.9f);
  EXPECT_EQ(status_of(side), core::DetectionStatus::degraded);  // one exact line: one side
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<float> u(-4.0f, 4.0f);
  for (int i = 0; i < 150; ++i) open.emplace_back(4.0f + u(rng), u(rng));
  const auto obs = det.detect(input_of(open));
  EXPECT_NE(obs.status, core::DetectionStatus::ok) << obs.rows.size() << " rows in an open field";
}

// A planar scan gives each corridor row only 8-12 returns after the voxel grid (issue 11): at
// the cloud label cost such a row's model is dropped, at planar_label_cost it is reported.
TEST(Pearl, SparsePlanarRowsKeepTheirModels) {
  int kept_planar = 0, kept_cloud = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.03);
    std::uniform_real_distribution<double> x(-0.5, 7.5);
    std::vector<Eigen::Vector2f> pts;
    for (const double y : {-1.0, 1.0})
      for (int i = 0; i < 9; ++i) pts.emplace_back(float(x(rng)), float(y + noise(rng)));
    for (const bool planar : {true, false}) {
      PearlDetector d(variant(PearlVariant::ruby, seed));
      DetectorInput in = input_of(pts);
      in.planar_scan = planar;
      (planar ? kept_planar : kept_cloud) += d.detect(in).corridor.has_value();
    }
  }
  std::printf("[sparse planar rows] corridor in %d / 20 (planar), %d / 20 (cloud label cost)\n",
              kept_planar, kept_cloud);
  EXPECT_GE(kept_planar, 19);
  EXPECT_LT(kept_cloud, kept_planar);
}

TEST(Pearl, SameSeedSameResult) {
  SyntheticRows s;
  s.weeds = 150;
  s.outliers = 20;
  const auto scene = make_rows(s);
  for (const auto v : {PearlVariant::pearl, PearlVariant::opal, PearlVariant::ruby}) {
    PearlDetector a(variant(v, 7)), b(variant(v, 7));
    const auto oa = a.detect(input_of(scene.points));
    a.detect(input_of(scene.points));
    const auto ob = b.detect(input_of(scene.points));
    const auto oa2 = a.detect(input_of(scene.points));
    ASSERT_EQ(oa.rows.size(), ob.rows.size());
    ASSERT_EQ(oa2.rows.size(), ob.rows.size());
    for (std::size_t i = 0; i < oa.rows.size(); ++i) {
      EXPECT_EQ(oa.rows[i].offset, ob.rows[i].offset);
      EXPECT_EQ(oa2.rows[i].offset, ob.rows[i].offset);
      EXPECT_EQ(oa.rows[i].support, ob.rows[i].support);
    }
  }
}

TEST(RansacLines, FindsCleanCorridorRows) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    SyntheticRows s;
    s.seed = seed;
    s.heading = 0.05 * static_cast<double>(seed % 5) - 0.1;
    const auto scene = make_rows(s);
    RansacLinesConfig c;
    c.seed = seed;
    RansacLinesDetector det(c);
    EXPECT_EQ(det.name(), "ransac_lines");
    const auto obs = det.detect(input_of(scene.points));
    const auto sc = test::score_corridor(obs, scene.truth, 1.0);
    EXPECT_EQ(obs.status, core::DetectionStatus::ok);
    EXPECT_EQ(sc.found, 2);
    EXPECT_LT(sc.heading_deg, 1.5);
    EXPECT_LT(sc.lateral, 0.05);  // measured worst 4.3 cm (canopy +-15 cm)
  }
}

TEST(RansacLines, DegenerateInputsAndDeterminism) {
  RansacLinesDetector det;
  EXPECT_EQ(det.detect(input_of({})).status, core::DetectionStatus::no_rows);
  EXPECT_EQ(det.detect(input_of({{1.0f, 0.5f}})).status, core::DetectionStatus::no_rows);
  std::vector<Eigen::Vector2f> wall;
  for (int i = 0; i < 200; ++i) wall.emplace_back(3.0f, -2.0f + 0.02f * static_cast<float>(i));
  EXPECT_EQ(det.detect(input_of(wall)).status, core::DetectionStatus::no_rows);
  EXPECT_EQ(det.detect(input_of(std::vector<Eigen::Vector2f>(50, {2.0f, 1.0f}))).status,
            core::DetectionStatus::no_rows);
  SyntheticRows s;
  s.weeds = 100;
  const auto scene = make_rows(s);
  RansacLinesDetector a, b;
  const auto oa = a.detect(input_of(scene.points)), ob = b.detect(input_of(scene.points));
  ASSERT_EQ(oa.rows.size(), ob.rows.size());
  for (std::size_t i = 0; i < oa.rows.size(); ++i) EXPECT_EQ(oa.rows[i].offset, ob.rows[i].offset);
}

}  // namespace
}  // namespace rownav::detect
