// Simulated pinhole RGB camera (Emmi 2021 Fig. 2b's camera), rendered by the ray caster.
#include "rownav/sim/pinhole_camera.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "rownav/sim/plant_geometry.hpp"

namespace rownav::sim {
namespace {

/// Horizontal square [-half, half]^2 at z = 0 centred at (cx, 0).
TriangleMesh ground(float half, float cx = 0.0f) {
  TriangleMesh m;
  const auto a = m.add_vertex({cx - half, -half, 0}), b = m.add_vertex({cx + half, -half, 0});
  const auto c = m.add_vertex({cx + half, half, 0}), d = m.add_vertex({cx - half, half, 0});
  m.add_triangle(a, b, c, SurfaceClass::ground);
  m.add_triangle(a, c, d, SurfaceClass::ground);
  return m;
}

/// Mean colour [0, 1] of the (2r+1)^2 pixels around (u, v).
Eigen::Vector3d mean_colour(const core::CameraImage& img, int u, int v, int r) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (int dv = -r; dv <= r; ++dv)
    for (int du = -r; du <= r; ++du) {
      const int x = u + du, y = v + dv;
      if (x < 0 || y < 0 || x >= img.width() || y >= img.height()) continue;
      const std::uint8_t* p = img.pixel(x, y);
      sum += Eigen::Vector3d(p[0], p[1], p[2]) / 255.0;
      ++n;
    }
  return n > 0 ? Eigen::Vector3d(sum / n) : sum;
}

/// Chromaticity (r, g, b) / (r + g + b): independent of the shading.
Eigen::Vector3d chroma(const Eigen::Vector3d& c) {
  return c / std::max(c.sum(), 1e-9);
}

/// Pixel of a base-frame point, or (-1, -1) outside the image.
Eigen::Vector2i pixel_of(const core::CameraImage& img, const Eigen::Vector3d& p_base) {
  const auto uv = img.intrinsics.project(img.T_base_camera.inverse() * p_base, 0.05);
  if (!uv) return {-1, -1};
  return {static_cast<int>(uv->x()), static_cast<int>(uv->y())};
}

TEST(PinholeCamera, SeesRandomPillarsWhereTheGeometryProjectsThem) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ux(3.0, 8.0), uy(-2.0, 2.0);
  PinholeCameraConfig c;
  c.shadows = false;  // the pillar's own shadow must not change what the test compares
  for (int trial = 0; trial < 8; ++trial) {
    const Eigen::Vector2d at(ux(rng), uy(rng));
    TriangleMesh m = ground(40.0f);
    add_cylinder(m, Eigen::Vector3f(at.x(), at.y(), 0.0f), Eigen::Vector3f(at.x(), at.y(), 2.0f),
                 0.25f, 8, SurfaceClass::post, true);
    const RayCaster world(m);
    PinholeCamera cam(c, 5);
    const auto img = cam.render(world, Eigen::Isometry3d::Identity(), 0.0);
    ASSERT_TRUE(img.valid());
    const Eigen::Vector2i on = pixel_of(img, {at.x(), at.y(), 0.4});
    ASSERT_GE(on.x(), 0) << "pillar " << trial << " projects outside the image";
    const Eigen::Vector3d post = chroma(c.post_colour), soil = chroma(c.ground_colour);
    const Eigen::Vector3d seen = chroma(mean_colour(img, on.x(), on.y(), 1));
    EXPECT_LT((seen - post).norm(), 0.03) << "trial " << trial;
    EXPECT_GT((seen - soil).norm(), 0.05) << "trial " << trial;  // not the soil around it
    // A metre beside the pillar (same depth) is soil.
    const Eigen::Vector2i beside = pixel_of(img, {at.x(), at.y() + 1.0, 0.0});
    if (beside.x() >= 0) {
      EXPECT_LT((chroma(mean_colour(img, beside.x(), beside.y(), 1)) - soil).norm(), 0.03);
    }
  }
}

TEST(PinholeCamera, MissesShowTheSky) {
  PinholeCameraConfig c;
  c.mount_rpy_deg = {0.0, -30.0, 0.0};  // looking up: the upper half of the image is sky
  const RayCaster world(ground(40.0f));
  PinholeCamera cam(c, 1);
  const auto img = cam.render(world, Eigen::Isometry3d::Identity(), 2.5);
  EXPECT_DOUBLE_EQ(img.stamp, 2.5);
  EXPECT_LT((mean_colour(img, c.width / 2, 2, 2) - c.sky_colour).norm(), 0.03);
}

TEST(PinholeCamera, ShadowedGroundIsLitOnlyByTheAmbientShare) {
  // A roof at 3 m over x in [5, 9]; the sun straight above: the ground under it is in shadow.
  PinholeCameraConfig c;
  c.sun_direction = {0.0, 0.0, 1.0};
  c.texture_variation = 0.0;
  TriangleMesh m = ground(40.0f);
  const auto a = m.add_vertex({5, -20, 3}), b = m.add_vertex({9, -20, 3});
  const auto d = m.add_vertex({9, 20, 3}), e = m.add_vertex({5, 20, 3});
  m.add_triangle(a, b, d, SurfaceClass::other);
  m.add_triangle(a, d, e, SurfaceClass::other);
  const RayCaster world(m);
  PinholeCamera cam(c, 3);
  const auto img = cam.render(world, Eigen::Isometry3d::Identity(), 0.0);
  const Eigen::Vector2i lit = pixel_of(img, {3.0, 0.0, 0.0}), dark = pixel_of(img, {7.0, 0.0, 0.0});
  ASSERT_GE(lit.x(), 0);
  ASSERT_GE(dark.x(), 0);
  const double lit_sum = mean_colour(img, lit.x(), lit.y(), 2).sum();
  const double dark_sum = mean_colour(img, dark.x(), dark.y(), 2).sum();
  EXPECT_NEAR(lit_sum, c.ground_colour.sum(), 0.05);
  EXPECT_NEAR(dark_sum / lit_sum, c.ambient, 0.05);
  c.shadows = false;  // without shadow rays both are lit
  PinholeCamera flat(c, 3);
  const auto img2 = flat.render(world, Eigen::Isometry3d::Identity(), 0.0);
  EXPECT_NEAR(mean_colour(img2, dark.x(), dark.y(), 2).sum(), lit_sum, 0.05);
}

TEST(PinholeCamera, CropOutsideTheTargetRegionTakesTheOtherCropColour) {
  PinholeCameraConfig c;
  c.use_target_region = true;
  c.target_min = {-50.0, -50.0};
  c.target_max = {50.0, 0.0};  // y > 0: the neighbouring field
  c.shadows = false;
  TriangleMesh m = ground(40.0f);
  for (const float y : {-1.0f, 1.0f})
    add_cylinder(m, Eigen::Vector3f(5, y, 0), Eigen::Vector3f(5, y, 1), 0.3f, 8, SurfaceClass::crop,
                 true);
  const RayCaster world(m);
  PinholeCamera cam(c, 4);
  const auto img = cam.render(world, Eigen::Isometry3d::Identity(), 0.0);
  const Eigen::Vector2i right = pixel_of(img, {5.0, -1.0, 0.5}),
                        left = pixel_of(img, {5.0, 1.0, 0.5});
  EXPECT_LT((chroma(mean_colour(img, right.x(), right.y(), 1)) - chroma(c.crop_colour)).norm(),
            0.03);
  EXPECT_LT((chroma(mean_colour(img, left.x(), left.y(), 1)) - chroma(c.other_crop_colour)).norm(),
            0.03);
}

TEST(PinholeCamera, TheSameSeedGivesTheSameImageAnotherSeedOtherNoise) {
  const RayCaster world(ground(40.0f));
  PinholeCamera a({}, 9), b({}, 9), other({}, 10);
  const auto ia = a.render(world, Eigen::Isometry3d::Identity(), 0.0);
  EXPECT_EQ(ia.rgb, b.render(world, Eigen::Isometry3d::Identity(), 0.0).rgb);
  EXPECT_NE(ia.rgb, other.render(world, Eigen::Isometry3d::Identity(), 0.0).rgb);
}

TEST(PinholeCamera, ANonFinitePoseGivesASkyImageWithoutThrowing) {
  const RayCaster world(ground(40.0f));
  PinholeCameraConfig c;
  c.pixel_noise_std = 0.0;
  PinholeCamera cam(c, 1);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation().x() = std::nan("");
  const auto img = cam.render(world, T, 0.0);
  ASSERT_TRUE(img.valid());
  EXPECT_LT((mean_colour(img, c.width / 2, c.height - 3, 2) - c.sky_colour).norm(), 0.01);
}

TEST(PinholeCamera, InvalidConfigsNameTheField) {
  PinholeCameraConfig c;
  c.horizontal_fov_deg = 180.0;
  try {
    PinholeCamera cam(c, 1);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("horizontal_fov_deg"), std::string::npos);
  }
  c = {};
  c.crop_colour = {1.2, 0.0, 0.0};
  EXPECT_THROW(PinholeCamera(c, 1), std::invalid_argument);
}

TEST(PinholeCameraConfig, IntrinsicsFollowTheFieldOfViewAndTheMountLooksForwardDown) {
  PinholeCameraConfig c;
  c.horizontal_fov_deg = 90.0;
  const auto k = c.intrinsics();
  EXPECT_NEAR(k.fx, c.width / 2.0, 1e-9);
  EXPECT_NEAR(k.cx, c.width / 2.0, 1e-9);
  const Eigen::Vector3d view = c.T_base_camera().linear() * Eigen::Vector3d::UnitZ();
  EXPECT_GT(view.x(), 0.8);   // forward
  EXPECT_LT(view.z(), -0.3);  // pitched 25 deg down
  const Eigen::Vector3d right = c.T_base_camera().linear() * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(right.y(), -1.0, 1e-9);  // image x is the robot's right
}

}  // namespace
}  // namespace rownav::sim
