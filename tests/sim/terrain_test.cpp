#include "rownav/sim/terrain.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "rownav/core/angle.hpp"

namespace rownav::sim {
namespace {

TEST(Terrain, FlatWithoutSlopeOrRoughness) {
  TerrainConfig c;
  c.roughness = 0.0;
  const Terrain t(c);
  EXPECT_DOUBLE_EQ(t.height(13.0, -7.0), 0.0);
  EXPECT_NEAR(t.normal(3.0, 4.0).z(), 1.0, 1e-12);
}

TEST(Terrain, SlopeGivesHeightAndNormal) {
  TerrainConfig c;
  c.roughness = 0.0;
  c.slope_x_deg = 10.0;
  c.slope_y_deg = -5.0;
  const Terrain t(c);
  EXPECT_NEAR(t.height(10.0, 0.0), 10.0 * std::tan(core::deg2rad(10.0)), 1e-9);
  EXPECT_NEAR(t.height(0.0, 10.0), -10.0 * std::tan(core::deg2rad(5.0)), 1e-9);
  const Eigen::Vector3d n = t.normal(1.0, 2.0);
  EXPECT_NEAR(n.norm(), 1.0, 1e-12);
  EXPECT_LT(n.x(), 0.0);  // ground rises with x: normal leans back
  EXPECT_GT(n.y(), 0.0);
  // Tilt of the normal from vertical equals the combined slope.
  const double gx = std::tan(core::deg2rad(10.0)), gy = std::tan(core::deg2rad(5.0));
  EXPECT_NEAR(std::acos(n.z()), std::atan(std::hypot(gx, gy)), 1e-9);
}

TEST(Terrain, RoughnessStdAndSmoothnessAndDeterminism) {
  TerrainConfig c;
  c.roughness = 0.05;
  c.roughness_wavelength = 2.0;
  c.seed = 7;
  const Terrain t(c), t2(c);
  double sum = 0.0, sum2 = 0.0, max_step = 0.0;
  int n = 0;
  for (double x = 0.0; x < 60.0; x += 0.25)
    for (double y = 0.0; y < 60.0; y += 0.25) {
      const double z = t.height(x, y);
      sum += z;
      sum2 += z * z;
      ++n;
      max_step = std::max(max_step, std::abs(t.height(x + 0.05, y) - z));
      ASSERT_EQ(z, t2.height(x, y));
    }
  const double sd = std::sqrt(sum2 / n - (sum / n) * (sum / n));
  EXPECT_GT(sd, 0.03);
  EXPECT_LT(sd, 0.07);
  EXPECT_LT(max_step, 0.05);  // smooth: < 5 cm over 5 cm
  // Normal agrees with the numerical gradient.
  const double h = 1e-4, x = 3.3, y = 4.4;
  const Eigen::Vector3d num(-(t.height(x + h, y) - t.height(x - h, y)) / (2 * h),
                            -(t.height(x, y + h) - t.height(x, y - h)) / (2 * h), 1.0);
  EXPECT_LT((num.normalized() - t.normal(x, y)).norm(), 1e-6);
  c.seed = 8;
  EXPECT_NE(Terrain(c).height(1.0, 1.0), t.height(1.0, 1.0));
}

TEST(Terrain, MeshCoversTheAreaAtCellSize) {
  TerrainConfig c;
  c.cell_size = 0.5;
  const Terrain t(c);
  const TriangleMesh m = t.mesh({-1.0, -2.0}, {9.0, 3.0});
  EXPECT_EQ(m.triangle_count(), 2u * 20u * 10u);
  EXPECT_EQ(m.labels.front(), SurfaceClass::ground);
  const auto b = m.bounds();
  EXPECT_NEAR(b.min().x(), -1.0, 1e-6);
  EXPECT_NEAR(b.max().y(), 3.0, 1e-6);
  for (const auto& v : m.vertices) ASSERT_NEAR(v.z(), t.height(v.x(), v.y()), 1e-5);
  // Triangles face up.
  const auto& tri = m.triangles.front();
  const Eigen::Vector3f nrm =
      (m.vertices[tri[1]] - m.vertices[tri[0]]).cross(m.vertices[tri[2]] - m.vertices[tri[0]]);
  EXPECT_GT(nrm.z(), 0.0f);
}

TEST(Terrain, ValidateNamesTheField) {
  TerrainConfig c;
  c.cell_size = 0.0;
  try {
    c.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cell_size"), std::string::npos);
  }
}

}  // namespace
}  // namespace rownav::sim
