// The chain on a simulated OS1-16 frame in a vineyard on a 4 deg slope (levelled base frame:
// the robot's base is gravity-aligned, so the slope shows in the base frame).
#include <gtest/gtest.h>

#include <limits>

#include "rownav/preprocess/preprocessor.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/lidar_presets.hpp"
#include "rownav/sim/ray_caster.hpp"

namespace rp = rownav::preprocess;
namespace sim = rownav::sim;

namespace {

struct Frame {
  rownav::core::PointCloud cloud;  // base frame; intensity holds the SurfaceClass label
};

Frame simulate(double slope_x_deg, double slope_y_deg) {
  sim::FieldConfig f;
  f.vineyard.rows = 6;
  f.vineyard.row_length = 30.0;
  f.terrain.slope_x_deg = slope_x_deg;
  f.terrain.slope_y_deg = slope_y_deg;
  const sim::Field field = sim::generate_field(f);
  const sim::RayCaster caster(field.mesh);
  const auto centre = sim::FieldTruth(field).corridor_centre(0, 2);  // a copy: the truth is a temporary
  const Eigen::Vector2d xy = centre[centre.size() / 2];
  const double z = field.terrain.height(xy.x(), xy.y());
  const sim::PoseAt pose_at = [&](double) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(xy.x(), xy.y(), z);
    return T;
  };
  const auto config = sim::lidar_preset("os1_16");
  sim::Lidar lidar(config, 5);
  std::vector<sim::SurfaceClass> labels;
  Frame frame;
  frame.cloud = lidar.sweep(caster, pose_at, 0.0, &labels);
  const Eigen::Isometry3f T = config.T_base_lidar().cast<float>();
  for (std::size_t i = 0; i < frame.cloud.points.size(); ++i) {
    auto& p = frame.cloud.points[i];
    const Eigen::Vector3f q = T * Eigen::Vector3f(p.x, p.y, p.z);
    p.x = q.x(), p.y = q.y(), p.z = q.z();
    p.intensity = static_cast<float>(labels[i]);
  }
  return frame;
}

struct Counts {
  std::size_t kept = 0, kept_ground = 0, canopy_in_crop = 0, canopy_kept = 0;
};

Counts run_chain(const Frame& frame, rp::GroundMethod method) {
  rp::PreprocessConfig c;
  c.voxel.voxel_size = 0.0;  // keep the original points, so their labels survive
  c.ground.method = method;
  rp::Preprocessor pre(c);
  const auto& out = pre.run(frame.cloud);
  const rp::CropBox box(c.crop);
  Counts n;
  const auto canopy = static_cast<float>(sim::SurfaceClass::canopy);
  for (const auto& p : frame.cloud.points)
    n.canopy_in_crop += p.intensity == canopy && box.contains(p.x, p.y, p.z);
  for (const auto& p : out.cloud.points) {
    ++n.kept;
    n.kept_ground += p.intensity == static_cast<float>(sim::SurfaceClass::ground);
    n.canopy_kept += p.intensity == canopy;
  }
  EXPECT_EQ(out.points.size(), out.cloud.points.size());
  return n;
}

}  // namespace

TEST(PreprocessSim, SlopedVineyardKeepsPlantsDropsGround) {
  const Frame frame = simulate(4.0, 2.0);
  ASSERT_GT(frame.cloud.size(), 5000u);
  for (auto method : {rp::GroundMethod::lowest_cell, rp::GroundMethod::ransac_plane}) {
    const Counts n = run_chain(frame, method);
    const auto name = rownav::core::enum_name(method);
    ASSERT_GT(n.kept, 500u) << name;
    EXPECT_LT(static_cast<double>(n.kept_ground), 0.05 * static_cast<double>(n.kept)) << name;
    EXPECT_GT(static_cast<double>(n.canopy_kept), 0.9 * static_cast<double>(n.canopy_in_crop))
        << name;
  }
  // A flat threshold (ground at base z = 0) keeps the rising ground ahead: the test can fail.
  const Counts flat = run_chain(frame, rp::GroundMethod::none);
  EXPECT_GT(static_cast<double>(flat.kept_ground), 0.1 * static_cast<double>(flat.kept));
}

TEST(PreprocessSim, VoxelAndScanOutputs) {
  const Frame frame = simulate(0.0, 0.0);
  rp::PreprocessConfig c;
  rp::Preprocessor pre(c);
  const std::size_t dense = pre.run(frame.cloud).cloud.size();
  c.use_scan = true;
  c.voxel.voxel_size = 0.0;
  rp::Preprocessor scan_pre(c);
  const auto& out = scan_pre.run(frame.cloud);
  EXPECT_EQ(out.scan.ranges.size(), 1081u);
  EXPECT_GT(out.points.size(), 100u);
  EXPECT_EQ(scan_pre.input(1.0).cloud, &out.cloud);
  for (const auto& p : out.points) EXPECT_LE(std::abs(p.y()), 4.0f + 1e-3f);
  EXPECT_GT(dense, 200u);
}

// The fused chain (crop pass; band + voxel pass) gives exactly the output of the steps run one
// after the other on copies: crop, ground estimate, height_band, VoxelGrid::filter.
TEST(PreprocessSim, FusedChainEqualsSeparateSteps) {
  Frame frame = simulate(4.0, 2.0);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < frame.cloud.points.size(); i += 97) frame.cloud.points[i].y = nan;
  for (std::size_t i = 5; i < frame.cloud.points.size(); i += 101)
    frame.cloud.points[i].z = std::numeric_limits<float>::infinity();
  for (auto method : {rp::GroundMethod::lowest_cell, rp::GroundMethod::ransac_plane})
    for (const double voxel : {0.15, 0.0}) {
      rp::PreprocessConfig c;
      c.ground.method = method;
      c.voxel.voxel_size = voxel;
      rp::Preprocessor pre(c);
      pre.run(frame.cloud);  // a second run reuses the buffers
      const auto& out = pre.run(frame.cloud);
      const rp::CropBox box(c.crop);
      std::vector<rownav::core::PointXYZIRT> cropped, band, ref;
      std::size_t invalid = 0;
      for (const auto& p : frame.cloud.points) {
        invalid += !p.finite();
        if (p.finite() && box.contains(p.x, p.y, p.z)) cropped.push_back(p);
      }
      rp::GroundEstimator ground(c.ground);
      EXPECT_EQ(out.ground_ok, ground.estimate(cropped));
      rp::height_band(cropped, ground, c.height, band);
      rp::VoxelGrid(c.voxel).filter(band, ref);
      SCOPED_TRACE(testing::Message() << rownav::core::enum_name(method) << " voxel " << voxel);
      EXPECT_EQ(out.dropped_invalid, invalid);
      ASSERT_EQ(out.cloud.points.size(), ref.size());
      ASSERT_EQ(out.points.size(), ref.size());
      ASSERT_GT(ref.size(), 300u);
      for (std::size_t i = 0; i < ref.size(); ++i) {
        const auto &a = out.cloud.points[i], &b = ref[i];
        ASSERT_EQ(a.x, b.x) << i;  // bit-identical: same points, same summation order
        ASSERT_EQ(a.y, b.y) << i;
        ASSERT_EQ(a.z, b.z) << i;
        ASSERT_EQ(a.intensity, b.intensity) << i;
        ASSERT_EQ(a.time, b.time) << i;
        ASSERT_EQ(a.ring, b.ring) << i;
        ASSERT_EQ(a.column, b.column) << i;
        ASSERT_EQ(out.points[i], Eigen::Vector2f(b.x, b.y)) << i;
      }
    }
}
