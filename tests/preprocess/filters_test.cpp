// Each preprocessing step on synthetic clouds with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "rownav/core/angle.hpp"
#include "rownav/preprocess/crop_box.hpp"
#include "rownav/preprocess/ground.hpp"
#include "rownav/preprocess/height_band.hpp"
#include "rownav/preprocess/radius_outlier.hpp"
#include "rownav/preprocess/scan_projection.hpp"
#include "rownav/preprocess/statistical_outlier.hpp"
#include "rownav/preprocess/voxel_grid.hpp"

namespace rp = rownav::preprocess;
using rownav::core::PointXYZIRT;

namespace {
PointXYZIRT pt(float x, float y, float z) {
  PointXYZIRT p;
  p.x = x, p.y = y, p.z = z;
  return p;
}
}  // namespace

TEST(CropBox, BoundariesAndRange) {
  rp::CropBoxConfig c;
  c.x_min = -1, c.x_max = 10, c.y_min = -4, c.y_max = 4, c.z_min = -1, c.z_max = 2;
  c.range_min = 0.5, c.range_max = 8.0;
  const rp::CropBox box(c);
  EXPECT_TRUE(box.contains(1.0f, 4.0f, 0.0f));     // on the y bound: inclusive
  EXPECT_FALSE(box.contains(1.0f, 4.01f, 0.0f));
  EXPECT_FALSE(box.contains(1.0f, -4.01f, 0.0f));
  EXPECT_FALSE(box.contains(-1.01f, 0.0f, 0.0f));
  EXPECT_FALSE(box.contains(1.0f, 0.0f, 2.01f));   // above z_max
  EXPECT_FALSE(box.contains(0.3f, 0.3f, 0.0f));    // r = 0.42 < range_min
  EXPECT_TRUE(box.contains(7.99f, 0.0f, 0.0f));
  EXPECT_FALSE(box.contains(7.0f, 3.9f, 0.0f));    // in the box, r = 8.01 > range_max
  EXPECT_TRUE(box.contains(5.0f, 1.0f));           // 2D test ignores z
  c.x_max = -2;
  EXPECT_THROW(rp::CropBox{c}, std::invalid_argument);
}

// CropBox::crop keeps exactly the finite points contains() accepts, in order, with their index,
// and counts NaN / Inf: with the range test (an annulus cutting the box) and without it (the
// default box lies inside range_max, so the test is skipped).
TEST(CropBox, CropEqualsContainsWithAndWithoutRangeTest) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> u(-12.0f, 12.0f);
  std::vector<PointXYZIRT> in;
  for (int i = 0; i < 20000; ++i) in.push_back(pt(u(rng), u(rng), u(rng) * 0.5f));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  in.push_back(pt(nan, 0.0f, 0.0f));
  in.push_back(pt(1.0f, nan, 0.0f));
  in.push_back(pt(1.0f, 0.0f, nan));
  in.push_back(pt(inf, 0.0f, 0.0f));
  in.push_back(pt(1.0f, -inf, 0.0f));
  in.push_back(pt(1.0f, 0.0f, inf));
  in.push_back(pt(10.0f, 4.0f, 0.0f));  // on the corner: inclusive
  rp::CropBoxConfig ring;
  ring.range_min = 0.5, ring.range_max = 8.0, ring.sensor_xy = {0.3, -0.2};
  for (const auto& c : {rp::CropBoxConfig{}, ring}) {
    const rp::CropBox box(c);
    std::vector<rp::CroppedPoint> out(3);  // only grown
    std::size_t invalid = 99;
    const std::size_t kept = box.crop(in, out, invalid);
    std::size_t n = 0;
    for (std::size_t i = 0; i < in.size(); ++i) {
      if (!in[i].finite() || !box.contains(in[i].x, in[i].y, in[i].z)) continue;
      ASSERT_LT(n, kept);
      EXPECT_EQ(out[n].index, i);
      EXPECT_EQ(out[n].x, in[i].x);
      EXPECT_EQ(out[n].y, in[i].y);
      EXPECT_EQ(out[n].z, in[i].z);
      ++n;
    }
    EXPECT_EQ(kept, n);
    EXPECT_GT(kept, 1000u);
    EXPECT_EQ(invalid, 6u);
  }
}

TEST(VoxelGrid, CentroidsAndCountsOnLattice) {
  // Lattice of spacing 0.05 over [0, 0.6)^2 x [0, 0.3): 12 x 12 x 6 points; 0.15 m voxels hold
  // 3 x 3 x 3 points each -> 4 x 4 x 2 voxels, centroids at the middle lattice point.
  std::vector<PointXYZIRT> in;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j)
      for (int k = 0; k < 6; ++k) in.push_back(pt(0.025f + 0.05f * i, 0.025f + 0.05f * j, 0.025f + 0.05f * k));
  rp::VoxelGrid grid(rp::VoxelGridConfig{0.15, 1});
  std::vector<PointXYZIRT> out;
  grid.filter(in, out);
  ASSERT_EQ(out.size(), 32u);
  for (const auto& p : out) {
    // centroid = voxel centre: 0.075 + 0.15 n
    for (float v : {p.x, p.y, p.z}) {
      const float n = (v - 0.075f) / 0.15f;
      EXPECT_NEAR(n, std::round(n), 1e-4f);
    }
  }
  // Negative coordinates: voxel [-0.15, 0) holds -0.01 and -0.14, not 0.01.
  std::vector<Eigen::Vector2f> in2{{-0.01f, 0.f}, {-0.14f, 0.f}, {0.01f, 0.f}};
  std::vector<Eigen::Vector2f> out2;
  grid.filter(in2, out2);
  ASSERT_EQ(out2.size(), 2u);
  EXPECT_NEAR(out2[0].x(), -0.075f, 1e-6f);
  EXPECT_NEAR(out2[1].x(), 0.01f, 1e-6f);
  // Reuse across frames and min points per voxel.
  rp::VoxelGrid strict(rp::VoxelGridConfig{0.15, 28});
  strict.filter(in, out);
  EXPECT_EQ(out.size(), 0u);
  strict.filter(std::span<const PointXYZIRT>{}, out);
  EXPECT_TRUE(out.empty());
}

TEST(Ransac, RecoversPlaneWith30PercentOutliers) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> u(-5.f, 5.f), h(0.2f, 3.f);
  std::normal_distribution<float> noise(0.f, 0.01f);
  const double a = 0.3, bx = std::tan(rownav::core::deg2rad(5.0)), cy = -0.04;
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 1000; ++i) {
    const float x = u(rng), y = u(rng);
    const float zg = static_cast<float>(a + bx * x + cy * y);
    pts.emplace_back(x, y, i % 10 < 3 ? zg + h(rng) : zg + noise(rng));
  }
  std::mt19937_64 r2(1);
  rp::GroundPlane plane;
  std::size_t inl = 0;
  ASSERT_TRUE(rp::ransac_plane(pts, 100, 0.05, 20.0, r2, plane, &inl));
  EXPECT_NEAR(plane[0], a, 0.01);
  EXPECT_NEAR(plane[1], bx, 0.003);
  EXPECT_NEAR(plane[2], cy, 0.003);
  EXPECT_NEAR(static_cast<double>(inl), 700.0, 15.0);
  // Same seed, same plane.
  std::mt19937_64 r3(1);
  rp::GroundPlane again;
  ASSERT_TRUE(rp::ransac_plane(pts, 100, 0.05, 20.0, r3, again));
  EXPECT_EQ(plane, again);
}

namespace {
/// 5 deg slope along x (ground z = tan(5 deg) x), ground points every 0.1 m, posts (0.05 m
/// wide, 2 m tall) every 2 m on two rows at y = +-1.25.
std::vector<PointXYZIRT> sloped_field(std::vector<bool>& is_post) {
  const float g = std::tan(static_cast<float>(rownav::core::deg2rad(5.0)));
  std::mt19937_64 rng(3);
  std::normal_distribution<float> noise(0.f, 0.01f);
  std::vector<PointXYZIRT> pts;
  for (float x = -1.f; x <= 10.f; x += 0.1f)
    for (float y = -4.f; y <= 4.f; y += 0.1f) {
      pts.push_back(pt(x, y, g * x + noise(rng)));
      is_post.push_back(false);
    }
  for (float x = 0.f; x <= 10.f; x += 2.f)
    for (float y : {-1.25f, 1.25f})
      for (float z = 0.f; z <= 2.f; z += 0.05f) {
        pts.push_back(pt(x, y, g * x + z));
        is_post.push_back(z >= 0.25f);  // the foot of a post is within the band's margin
      }
  return pts;
}
}  // namespace

TEST(HeightBand, SlopedGroundKeepsPostsDropsGround) {
  std::vector<bool> is_post;
  const auto pts = sloped_field(is_post);
  rp::HeightBandConfig band;  // 0.2 .. 3 m above ground
  for (auto method : {rp::GroundMethod::lowest_cell, rp::GroundMethod::ransac_plane}) {
    rp::GroundConfig gc;
    gc.method = method;
    rp::GroundEstimator ground(gc);
    ASSERT_TRUE(ground.estimate(pts));
    std::vector<PointXYZIRT> out;
    rp::height_band(pts, ground, band, out);
    std::size_t posts = 0, ground_pts = 0;
    for (const auto& p : out) {
      const float h = p.z - std::tan(static_cast<float>(rownav::core::deg2rad(5.0))) * p.x;
      (h > 0.1f ? posts : ground_pts)++;
    }
    std::size_t expected_posts = 0;
    for (bool b : is_post) expected_posts += b;
    EXPECT_EQ(ground_pts, 0u) << rownav::core::enum_name(method);
    EXPECT_GE(posts, expected_posts) << rownav::core::enum_name(method);
    EXPECT_NEAR(ground.ground_z(8.f, 2.f), 8.f * std::tan(rownav::core::deg2rad(5.0)), 0.05);
  }
  // A flat z threshold fails on this slope: ground at x > 2.3 m is above 0.2 m.
  rp::GroundConfig flat;
  flat.method = rp::GroundMethod::none;
  rp::GroundEstimator none(flat);
  none.estimate(pts);
  std::vector<PointXYZIRT> out;
  rp::height_band(pts, none, band, out);
  EXPECT_GT(out.size(), 3000u);
}

TEST(RadiusOutlier, DropsIsolatedKeepsRows) {
  std::vector<Eigen::Vector2f> pts;
  for (float x = 0.f; x < 8.f; x += 0.1f) pts.emplace_back(x, 1.25f), pts.emplace_back(x, -1.25f);
  const std::size_t row_points = pts.size();
  pts.emplace_back(3.f, 0.f);   // isolated
  pts.emplace_back(5.f, 0.4f);  // isolated
  pts.emplace_back(std::numeric_limits<float>::quiet_NaN(), 0.f);
  rp::RadiusOutlier f(rp::RadiusOutlierConfig{true, 0.3, 2});
  std::vector<Eigen::Vector2f> out;
  f.filter(pts, out);
  EXPECT_EQ(out.size(), row_points);
  for (const auto& p : out) EXPECT_NEAR(std::abs(p.y()), 1.25f, 1e-6f);
  // 3D: a pair 0.25 m apart keeps each other with min_neighbors 1, not 2.
  std::vector<PointXYZIRT> c{pt(0, 0, 0), pt(0, 0, 0.25f), pt(5, 5, 5)};
  std::vector<PointXYZIRT> o;
  rp::RadiusOutlier(rp::RadiusOutlierConfig{true, 0.3, 1}).filter(c, o);
  EXPECT_EQ(o.size(), 2u);
  rp::RadiusOutlier(rp::RadiusOutlierConfig{true, 0.3, 2}).filter(c, o);
  EXPECT_EQ(o.size(), 0u);
}

TEST(StatisticalOutlier, DropsIsolatedKeepsRows) {
  std::vector<Eigen::Vector2f> pts;
  for (float x = 0.f; x < 8.f; x += 0.1f) pts.emplace_back(x, 1.25f), pts.emplace_back(x, -1.25f);
  const std::size_t row_points = pts.size();
  pts.emplace_back(3.f, 0.f);
  pts.emplace_back(6.f, 0.1f);
  // Mean 8-NN distance: 0.25 m inside a row, 0.45 m at a row end, > 1 m isolated.
  rp::StatisticalOutlier f(rp::StatisticalOutlierConfig{true, 8, 3.0});
  std::vector<Eigen::Vector2f> out;
  f.filter(pts, out);
  EXPECT_EQ(out.size(), row_points);
  for (const auto& p : out) EXPECT_NEAR(std::abs(p.y()), 1.25f, 1e-6f);
  // A 1-sigma cut also drops the 4 row ends (PCL semantics).
  rp::StatisticalOutlier tight(rp::StatisticalOutlierConfig{true, 8, 1.0});
  tight.filter(pts, out);
  EXPECT_EQ(out.size(), row_points - 4);
  f.filter(std::span<const Eigen::Vector2f>{}, out);
  EXPECT_TRUE(out.empty());
}

TEST(ScanProjection, NearestReturnPerBinInfWhereEmpty) {
  rp::ScanProjectionConfig c;
  c.angle_min_deg = -90, c.angle_max_deg = 90, c.angle_increment_deg = 1.0;
  c.min_height = 0.2, c.max_height = 1.5, c.range_min = 0.3, c.range_max = 20;
  const rp::ScanProjection proj(c);
  ASSERT_EQ(c.bins(), 181u);
  const auto at = [](double deg, float r, float z) {
    const double a = rownav::core::deg2rad(deg);
    return pt(r * static_cast<float>(std::cos(a)), r * static_cast<float>(std::sin(a)), z);
  };
  std::vector<PointXYZIRT> cloud{at(30.5, 5.f, 1.f), at(30.2, 3.f, 1.f), at(30.8, 4.f, 1.f),
                                 at(-45.5, 2.f, 0.5f), at(-45.5, 1.f, 0.05f),  // below band
                                 at(10.5, 6.f, 2.f),                          // above band
                                 at(150.0, 2.f, 1.f),                         // outside fov
                                 at(0.5, 0.2f, 1.f)};                         // < range_min
  rownav::core::Scan2D scan;
  proj.project(cloud, nullptr, scan);
  ASSERT_EQ(scan.ranges.size(), 181u);
  EXPECT_FLOAT_EQ(scan.ranges[120], 3.f);  // bin [30, 31) deg: nearest of 3, 4, 5 m
  EXPECT_FLOAT_EQ(scan.ranges[44], 2.f);   // bin [-46, -45) deg
  EXPECT_NEAR(rownav::core::rad2deg(scan.angle(120)), 30.0, 1e-9);
  std::size_t finite = 0;
  for (float r : scan.ranges) finite += std::isfinite(r);
  EXPECT_EQ(finite, 2u);
  EXPECT_TRUE(std::isinf(scan.ranges[100]));
  EXPECT_TRUE(std::isinf(scan.ranges[90]));
  std::vector<Eigen::Vector2f> pts;
  rp::ScanProjection::to_points(scan, pts);
  ASSERT_EQ(pts.size(), 2u);
  EXPECT_NEAR(std::atan2(pts[1].y(), pts[1].x()), rownav::core::deg2rad(30.0), 1e-6);
}
