#include "rownav/detect/pipeline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/synthetic_rows.hpp"
#include "rownav/core/angle.hpp"
#include "rownav/detect/baseline.hpp"

namespace rownav::detect {
namespace {

Eigen::Isometry3d mount(double x, double y, double z, double yaw_deg) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::AngleAxisd(core::deg2rad(yaw_deg), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

// Two maize rows 0.75 m apart, straight ahead of the base.
test::SyntheticScene maize() {
  test::SyntheticRows s;
  s.rows = 2;
  s.spacing = 0.75;
  s.x_min = 0.2;
  s.x_max = 4.0;
  s.canopy_half_width = 0.03;
  s.point_spacing = 0.01;
  return test::make_rows(s);
}

// A scan in the LiDAR frame of points given in the base frame: each point goes to its beam,
// the nearest return wins.
core::Scan2D scan_of(const std::vector<Eigen::Vector2f>& base,
                     const Eigen::Isometry3d& T_base_lidar) {
  core::Scan2D scan;
  scan.angle_min = -core::deg2rad(135.0);
  scan.angle_increment = core::deg2rad(0.25);
  scan.range_min = 0.05;
  scan.range_max = 10.0;
  scan.ranges.assign(1081, std::numeric_limits<float>::infinity());
  const Eigen::Isometry2d T = planar_mount(T_base_lidar).inverse();
  for (const auto& p : base) {
    const Eigen::Vector2d q = T * p.cast<double>();
    const auto i = std::lround((std::atan2(q.y(), q.x()) - scan.angle_min) / scan.angle_increment);
    if (i < 0 || i >= 1081) continue;
    auto& r = scan.ranges[static_cast<std::size_t>(i)];
    r = std::min(r, static_cast<float>(q.norm()));
  }
  return scan;
}

// No voxel grid, so every kept point can be counted.
DetectionPipeline baseline_pipeline(const Eigen::Isometry3d& T) {
  preprocess::PreprocessConfig pre;
  pre.voxel.voxel_size = 0.0;
  return {pre, std::make_unique<BaselineDetector>(), T};
}

TEST(DetectionPipeline, ScanMountYawIsUndone) {
  const auto scene = maize();
  const Eigen::Isometry3d T = mount(0.3, 0.05, 0.4, 25.0);
  const core::Scan2D scan = scan_of(scene.points, T);
  auto mounted = baseline_pipeline(T);
  const auto obs = mounted.process(scan);
  ASSERT_EQ(obs.status, core::DetectionStatus::ok);
  EXPECT_NEAR(obs.rows[obs.left].offset, 0.375, 0.03);
  EXPECT_NEAR(obs.rows[obs.right].offset, -0.375, 0.03);
  EXPECT_NEAR(core::rad2deg(obs.heading), 0.0, 1.5);
  // Without the mount the rows come out turned against the yaw (the baseline's box clips them,
  // so not by the whole 25 deg).
  auto bare = baseline_pipeline(Eigen::Isometry3d::Identity());
  const auto raw = bare.process(scan);
  ASSERT_FALSE(raw.rows.empty());
  EXPECT_LT(core::rad2deg(raw.heading), -3.0);
}

TEST(DetectionPipeline, CloudGoesToTheBaseFrameBeforeTheHeightBand) {
  const auto scene = maize();
  const Eigen::Isometry3d T = mount(0.3, 0.0, 0.6, -30.0);
  core::PointCloud cloud;
  cloud.stamp = 4.5;
  const Eigen::Isometry3d T_lidar_base = T.inverse();
  for (const auto& p : scene.points)
    for (const double z : {0.05, 0.5}) {  // ground (dropped by the height band) and plants
      const Eigen::Vector3d q = T_lidar_base * Eigen::Vector3d(p.x(), p.y(), z);
      cloud.points.push_back(
          {static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z())});
    }
  cloud.points.push_back({std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f});
  auto p = baseline_pipeline(T);
  const auto obs = p.process(cloud);
  EXPECT_EQ(obs.stamp, 4.5);
  ASSERT_EQ(obs.status, core::DetectionStatus::ok);
  EXPECT_NEAR(obs.rows[obs.left].offset, 0.375, 0.03);
  EXPECT_NEAR(core::rad2deg(obs.heading), 0.0, 1.5);
  EXPECT_EQ(p.last_points().size(), scene.points.size());  // ground and NaN dropped
  EXPECT_EQ(p.detector().name(), "baseline");
}

TEST(DetectionPipeline, EmptyAndInvalidFramesGiveNoRows) {
  auto p = baseline_pipeline(Eigen::Isometry3d::Identity());
  EXPECT_EQ(p.process(core::PointCloud{}).status, core::DetectionStatus::no_rows);
  EXPECT_EQ(p.process(core::Scan2D{}).status, core::DetectionStatus::no_rows);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<Eigen::Vector2f> bad = {{nan, nan}, {1.0f, nan}};
  EXPECT_EQ(p.process_points(bad, 1.0).status, core::DetectionStatus::no_rows);
  EXPECT_THROW(DetectionPipeline(preprocess::PreprocessConfig{}, nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::detect
