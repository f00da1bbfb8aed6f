#include "rownav/detect/trunk_lines.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <sstream>

namespace rownav::detect {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A random orchard around a robot: rows along world x at y = (k + 0.5) spacing, the robot at
/// world (0, lateral) with yaw `yaw`; points in the base frame, z = height above flat ground.
struct Scene {
  double spacing = 5.0, tree_spacing = 4.0, crown_radius = 1.25, lateral = 0.0, yaw = 0.0;
  double missing = 0.1;  // share of trees missing
  bool trunks = true;    // false: crowns down to the ground, no trunk visible (a hedge)
  int weeds = 30;
  int crown_points = 80;
  bool occlude = false;  // true: only the corridor-facing half of each crown is seen
  core::PointCloud cloud;

  /// [m] the true offset at base x = 0 of the row at world y.
  double offset(double y) const { return (y - lateral) / std::cos(yaw); }

  void add(double x, double y, double z) {
    const double c = std::cos(yaw), s = std::sin(yaw), dx = x, dy = y - lateral;
    core::PointXYZIRT p;
    p.x = static_cast<float>(c * dx + s * dy), p.y = static_cast<float>(-s * dx + c * dy);
    p.z = static_cast<float>(z);
    if (std::hypot(p.x, p.y) < 12.0) cloud.points.push_back(p);
  }

  void build(std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double phase = u(rng) * tree_spacing;
    for (int k = -3; k <= 2; ++k)
      for (double x = -10.0 + phase; x < 16.0; x += tree_spacing) {
        if (u(rng) < missing) continue;
        const double tx = x + 0.1 * (u(rng) - 0.5), ty = (k + 0.5) * spacing + 0.1 * (u(rng) - 0.5);
        const double r = 0.05 + 0.1 * u(rng);
        if (trunks)
          for (int a = 0; a < 8; ++a)
            for (const double z : {0.35, 0.5, 0.65})
              add(tx + r * std::cos(a * kPi / 4), ty + r * std::sin(a * kPi / 4), z);
        const double base = trunks ? 0.8 : 0.1;
        for (int i = 0; i < crown_points; ++i) {  // crown: points of a spherical shell
          const double th = 2 * kPi * u(rng), ph = std::acos(2 * u(rng) - 1);
          const double z = base + crown_radius * (1 + std::cos(ph));
          const double py = ty + crown_radius * std::sin(ph) * std::sin(th);
          if (occlude && (py - ty) * (ty - lateral) > 0.0) continue;  // far side: hidden
          add(tx + crown_radius * std::sin(ph) * std::cos(th), py, z);
        }
      }
    const double free = std::max(0.0, 0.5 * spacing - crown_radius - 0.25);
    for (int i = 0; i < weeds; ++i)  // low weeds in the open strip of the corridor
      add(-5.0 + 20.0 * u(rng), (2 * u(rng) - 1) * free, 0.05 + 0.2 * u(rng));
  }
};

/// Both corridor rows within `tol` [m] of the truth at x = 0 and the heading within 1 deg.
::testing::AssertionResult corridor_found(const core::RowObservation& obs, const Scene& s,
                                          double tol) {
  if (obs.left < 0 || obs.right < 0) return ::testing::AssertionFailure() << "a side is missing";
  const double l = obs.rows[std::size_t(obs.left)].offset, r = obs.rows[std::size_t(obs.right)].offset;
  const double el = l - s.offset(0.5 * s.spacing), er = r - s.offset(-0.5 * s.spacing);
  const double eh = obs.heading + s.yaw;
  if (std::abs(el) > tol || std::abs(er) > tol || std::abs(eh) > kPi / 180.0)
    return ::testing::AssertionFailure()
           << "left error " << el << ", right error " << er << ", heading error " << eh;
  return ::testing::AssertionSuccess();
}

TEST(TrunkLines, FindsTheCorridorRowsOnTheirTrunksOffCentreAndYawed) {
  // Seeded random orchards: spacing 3-7 m, trees 1.5-6 m apart, crowns 0.5-2 m in radius but
  // narrower than the spacing, the robot up to 40 % of the half corridor off centre, +-10 deg.
  TrunkLinesDetector d;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int ok = 0, n = 100;
  std::ostringstream failures;
  for (int i = 0; i < n; ++i) {
    Scene s;
    s.spacing = 3.0 + 4.0 * u(rng);
    s.tree_spacing = 1.5 + 4.5 * u(rng);
    s.crown_radius = std::min(0.5 + 1.5 * u(rng), 0.35 * s.spacing);
    s.lateral = (2 * u(rng) - 1) * 0.4 * (0.5 * s.spacing - s.crown_radius);
    s.yaw = (2 * u(rng) - 1) * 10.0 * kPi / 180.0;
    s.build(100 + static_cast<std::uint64_t>(i));
    DetectorInput in;
    in.cloud = &s.cloud;
    const auto obs = d.detect(in);
    const auto found = corridor_found(obs, s, 0.1);
    if (found) {
      ++ok;
      EXPECT_TRUE(obs.rows[std::size_t(obs.left)].centre_line);
    } else {
      failures << "scene " << i << " (spacing " << s.spacing << ", trees " << s.tree_spacing
               << "): " << found.message() << "\n";
    }
  }
  // Measured: 100 / 100; a miss is listed, not hidden.
  EXPECT_GE(ok, 98) << failures.str();
}

TEST(TrunkLinesCentres, AreTheCompactClustersOfTheTrunkBand) {
  Scene s;
  s.missing = 0.0;
  s.weeds = 0;
  s.build(3);
  TrunkCentres f;
  const auto& trunks = f.find(s.cloud, {});
  ASSERT_GE(trunks.size(), 10u);
  for (const auto& t : trunks) {  // every centre within 0.1 m of a row line
    const double w = t.centre.y() + s.lateral;
    const double to_row = std::abs(std::remainder(w - 0.5 * s.spacing, s.spacing));
    EXPECT_LT(to_row, 0.1) << t.centre.transpose();
  }
}

TEST(TrunkLines, ALineOfTallWeedsWithoutCrownIsNoRow) {
  Scene s;
  s.build(5);
  // Weeds in the trunk band, lined up along the corridor centre: trunk-like clusters, no crown.
  for (double x = 1.0; x < 10.0; x += 2.0)
    for (int k = 0; k < 6; ++k) s.add(x + 0.02 * k, s.lateral + 0.01 * k, 0.4 + 0.03 * k);
  TrunkLinesDetector d;
  DetectorInput in;
  in.cloud = &s.cloud;
  EXPECT_TRUE(corridor_found(d.detect(in), s, 0.1));
}

TEST(TrunkLines, WithoutTrunksFallsBackToTheCrownDetector) {
  Scene s;
  s.trunks = false;
  s.spacing = 4.0;
  s.crown_radius = 0.8;
  s.tree_spacing = 0.5;  // a hedge, seen from the corridor only
  s.occlude = true;
  s.crown_points = 600;  // a dense face: its band points form one long cluster, no trunk
  s.build(9);
  TrunkLinesDetector d;
  DetectorInput in;
  in.cloud = &s.cloud;
  for (const auto& p : s.cloud.points) in.points.emplace_back(p.x, p.y);  // as the preprocessor
  const auto obs = d.detect(in);
  ASSERT_GE(obs.left, 0);
  ASSERT_GE(obs.right, 0);
  // The rows stand on the corridor-side half of the crowns, between face and row line.
  // Known miss: clusters of a hedge face's lowest band can pass as trunks, and such a row is
  // then marked as a centre line (a spacing from it is a face-to-face width); trunk_lines is
  // the orchard default, hedge vineyards keep hough_skew + row_profile.
  const double left = obs.rows[std::size_t(obs.left)].offset;
  EXPECT_GT(left, s.offset(2.0) - 0.8 - 0.1);  // not nearer than the face
  EXPECT_LT(left, s.offset(2.0) + 0.1);        // not beyond the row line
}

TEST(TrunkLines, NonFiniteAndEmptyInputGiveNoRowsWithoutThrowing) {
  TrunkLinesDetector d;
  core::PointCloud c;
  DetectorInput in;
  in.cloud = &c;
  EXPECT_EQ(d.detect(in).status, core::DetectionStatus::no_rows);
  core::PointXYZIRT p;
  p.x = p.y = p.z = std::numeric_limits<float>::quiet_NaN();
  c.points.assign(50, p);
  EXPECT_EQ(d.detect(in).status, core::DetectionStatus::no_rows);
}

TEST(TrunkLinesConfig, ValidateNamesTheField) {
  TrunkLinesConfig c;
  c.min_trunks = 1;
  try {
    c.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("min_trunks"), std::string::npos);
  }
  c = {};
  c.trunks.z_max = 0.1;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::detect
