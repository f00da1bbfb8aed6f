// The chain's bookkeeping: NaN / Inf dropped and counted, empty input, 2D input, buffer reuse.
#include <gtest/gtest.h>

#include <limits>

#include "rownav/preprocess/preprocessor.hpp"

namespace rp = rownav::preprocess;

TEST(Preprocessor, DropsAndCountsInvalid3D) {
  rownav::core::PointCloud cloud;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (float x = 1.f; x < 6.f; x += 0.05f) {
    rownav::core::PointXYZIRT g, t;
    g.x = x, g.y = 0.5f, g.z = 0.f;    // ground
    t.x = x, t.y = 1.25f, t.z = 1.0f;  // canopy
    cloud.points.push_back(g), cloud.points.push_back(t);
  }
  rownav::core::PointXYZIRT bad;
  bad.x = nan;
  cloud.points.push_back(bad);
  bad.x = 1.f, bad.z = inf;
  cloud.points.push_back(bad);
  rp::PreprocessConfig c;
  c.ground.method = rp::GroundMethod::none;
  rp::Preprocessor pre(c);
  const auto& out = pre.run(cloud);
  EXPECT_EQ(out.dropped_invalid, 2u);
  // 5 m of canopy at 0.05 m spacing in 0.15 m voxels: 34 voxels (x in [0.9, 6.0)).
  EXPECT_NEAR(static_cast<double>(out.cloud.size()), 34.0, 1.0);
  for (const auto& p : out.points) EXPECT_NEAR(p.y(), 1.25f, 1e-5f);
  const auto in = pre.input(3.0);
  EXPECT_EQ(in.cloud, &out.cloud);
  EXPECT_EQ(in.points.size(), out.points.size());
  // Empty input: nothing kept, nothing thrown, ground falls back to flat.
  const auto& empty = pre.run(rownav::core::PointCloud{});
  EXPECT_TRUE(empty.cloud.points.empty());
  EXPECT_TRUE(empty.points.empty());
  EXPECT_EQ(empty.dropped_invalid, 0u);
}

TEST(Preprocessor, TwoDInputCropAndCount) {
  rp::PreprocessConfig c;
  c.voxel.voxel_size = 0.0;
  c.radius_outlier.enabled = true;
  rp::Preprocessor pre(c);
  std::vector<Eigen::Vector2f> pts;
  for (int i = 0; i < 120; ++i) {
    const float x = 0.05f + 0.1f * static_cast<float>(i);
    pts.emplace_back(x, 1.25f), pts.emplace_back(x, -5.f);
  }
  pts.emplace_back(std::numeric_limits<float>::quiet_NaN(), 0.f);
  pts.emplace_back(4.f, 0.f);  // isolated: radius outlier
  const auto& out = pre.run(pts);
  EXPECT_EQ(out.dropped_invalid, 1u);
  EXPECT_EQ(out.points.size(), 100u);  // x in [0.05, 9.95] of the y = 1.25 row
  EXPECT_EQ(pre.input(0.0).cloud, nullptr);
  EXPECT_TRUE(pre.run(std::span<const Eigen::Vector2f>{}).points.empty());
}

TEST(PreprocessConfig, ValidateNamesField) {
  rp::PreprocessConfig c;
  c.voxel.voxel_size = -1.0;
  try {
    c.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("voxel.voxel_size"), std::string::npos);
  }
}
