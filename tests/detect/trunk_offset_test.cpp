#include "rownav/detect/trunk_offset.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace rownav::detect {
namespace {

core::PointXYZIRT point(double x, double y, double z) {
  core::PointXYZIRT p;
  p.x = static_cast<float>(x), p.y = static_cast<float>(y), p.z = static_cast<float>(z);
  return p;
}

/// A row along x at y = `row`: trunks every metre (z 0.2-0.35), canopy (z 0.5-1.5) whose
/// visible face lies 0.2 m towards the robot, weeds (z 0.2-0.4) 0.45-0.9 m towards it.
core::PointCloud row_cloud(double row, int trunks, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  core::PointCloud c;
  const double in = row > 0.0 ? -1.0 : 1.0;  // towards the robot
  for (int t = 0; t < trunks; ++t)
    for (int k = 0; k < 3; ++k)
      c.points.push_back(point(1.0 + t, row + in * 0.02 + 0.01 * (u(rng) - 0.5), 0.2 + 0.05 * k));
  for (int i = 0; i < 300; ++i)
    c.points.push_back(point(8.0 * u(rng), row + in * (0.2 + 0.05 * u(rng)), 0.5 + u(rng)));
  for (int i = 0; i < 10; ++i)
    c.points.push_back(point(8.0 * u(rng), row + in * (0.45 + 0.45 * u(rng)), 0.2 + 0.2 * u(rng)));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  c.points.push_back(point(nan, nan, 0.3));
  return c;
}

TEST(TrunkOffset, MovesCanopyLineOntoTrunks) {
  TrunkOffset t;
  for (const double row : {0.9, -0.9}) {
    const auto cloud = row_cloud(row, 7, 1);
    ASSERT_GT(t.collect(cloud, Eigen::Vector2d::UnitX()), 20u);
    const double canopy = row + (row > 0.0 ? -0.2 : 0.2);  // the fitted canopy face
    EXPECT_NEAR(t.offset(canopy), row + (row > 0.0 ? -0.02 : 0.02), 0.01) << row;
    core::RowLine r;
    r.line = core::Line2(Eigen::Vector2d(0.0, canopy), Eigen::Vector2d::UnitX());
    r.offset = canopy;
    EXPECT_NEAR(t.apply(r), (row > 0.0 ? 0.18 : -0.18), 0.01);
    EXPECT_NEAR(r.offset, r.line.y_at(0.0), 1e-12);
  }
}

TEST(TrunkOffset, KeepsCanopyWithoutEnoughTrunks) {
  TrunkOffset t;
  const auto cloud = row_cloud(0.9, 1, 2);  // 3 trunk points < min_points, weeds out of reach
  t.collect(cloud, Eigen::Vector2d::UnitX());
  EXPECT_EQ(t.offset(0.7), 0.7);
  TrunkOffsetConfig off;
  off.enabled = false;
  TrunkOffset disabled(off);
  EXPECT_EQ(disabled.collect(row_cloud(0.9, 7, 3), Eigen::Vector2d::UnitX()), 0u);
  EXPECT_EQ(disabled.offset(0.7), 0.7);
}

TEST(TrunkOffset, ConfigValidation) {
  TrunkOffsetConfig c;
  c.z_max = c.z_min;
  EXPECT_THROW(TrunkOffset{c}, std::invalid_argument);
  c = {};
  c.min_points = 0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::detect
