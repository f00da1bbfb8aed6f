#include "rownav/localize/cloud_accumulator.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rownav::localize {
namespace {

/// Localizer fed a straight drive at 1 m/s along x for 2 s (differential, encoders at 50 Hz).
Localizer moving_localizer() {
  LocalizerConfig c;
  c.odometry.model = DriveModel::differential;
  c.use_imu = false;
  Localizer loc(c);
  const double m_per_tick = 2.0 * M_PI * c.odometry.wheel_radius / c.odometry.ticks_per_rev;
  for (int i = 0; i <= 100; ++i) {
    const double t = i * 0.02;
    const auto ticks = static_cast<std::int64_t>(std::floor(t / m_per_tick));
    loc.add_encoders({t, ticks, ticks, 0.0});
  }
  return loc;
}

/// A sweep of a wall at world x = 10 m, one column every 10 ms, seen by a sensor at the base
/// origin while the robot moves: the raw point x shrinks by the distance driven.
core::PointCloud wall_sweep(const Localizer& loc, double stamp) {
  core::PointCloud c;
  c.stamp = stamp;
  c.has_time = true;
  for (int k = 0; k < 10; ++k) {
    const double t = 0.01 * k;
    const double x_base = loc.T_odom_base(stamp + t)->x;
    core::PointXYZIRT p;
    p.x = static_cast<float>(10.0 - x_base);
    p.y = static_cast<float>(-1.0 + 0.2 * k);
    p.time = static_cast<float>(t);
    c.points.push_back(p);
  }
  core::PointXYZIRT bad;
  bad.x = std::nanf("");
  c.points.push_back(bad);
  return c;
}

TEST(CloudAccumulator, DeskewStraightensWallAndAccumulates) {
  const Localizer loc = moving_localizer();
  CloudAccumulator acc;
  const auto r = acc.add(wall_sweep(loc, 1.0), Eigen::Isometry3d::Identity(), loc);
  EXPECT_EQ(r.status, AccumulateStatus::ok);
  EXPECT_EQ(r.points, 10u);
  EXPECT_EQ(r.dropped, 1u);
  acc.add(wall_sweep(loc, 1.2), Eigen::Isometry3d::Identity(), loc);
  const core::PointCloud out = acc.latest_in_base();
  ASSERT_EQ(out.size(), 20u);
  // In the base frame at the newest sweep's start, the wall is at 10 - x(1.2) for every point.
  const double expected = 10.0 - loc.T_odom_base(1.2)->x;
  for (const auto& p : out.points) EXPECT_NEAR(p.x, expected, 1e-4);
  // Without deskewing the raw sweep spreads by the 9 cm driven during it.
  CloudAccumulatorConfig c;
  c.deskew = false;
  CloudAccumulator raw(c);
  raw.add(wall_sweep(loc, 1.0), Eigen::Isometry3d::Identity(), loc);
  const auto pts = raw.latest_in_base().points;
  EXPECT_GT(pts.front().x - pts.back().x, 0.08);
}

TEST(CloudAccumulator, KeepsLastSweepsAndNeedsPose) {
  const Localizer loc = moving_localizer();
  CloudAccumulatorConfig c;
  c.sweeps = 2;
  CloudAccumulator acc(c);
  for (double t : {0.5, 0.7, 0.9}) acc.add(wall_sweep(loc, t), Eigen::Isometry3d::Identity(), loc);
  EXPECT_EQ(acc.sweeps(), 2u);
  core::PointCloud far;
  far.stamp = 50.0;
  far.points.resize(3);
  EXPECT_EQ(acc.add(far, Eigen::Isometry3d::Identity(), loc).status, AccumulateStatus::no_pose);
  EXPECT_EQ(acc.sweeps(), 2u);
}

}  // namespace
}  // namespace rownav::localize
