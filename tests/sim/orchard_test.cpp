#include "rownav/sim/orchard.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace rownav::sim {
namespace {

TEST(Orchard, TreeAndRowSpacingAsConfigured) {
  OrchardConfig c;
  c.rows = 5;
  c.row_length = 60.0;
  c.row_spacing = 5.5;
  c.tree_spacing = 4.0;
  c.missing_trees_percent = 0.0;
  TerrainConfig t;
  t.slope_x_deg = 3.0;
  const Field f = generate_orchard(c, t, 3);
  ASSERT_EQ(f.rows.size(), 5u);
  EXPECT_EQ(f.kind, FieldKind::orchard);
  for (std::size_t k = 0; k < 5; ++k) EXPECT_NEAR(f.rows[k].start().y(), 5.5 * k, 1e-9);
  std::vector<double> xs;
  for (const auto& p : f.plants)
    if (p.kind == PlantKind::tree && p.row == 2) xs.push_back(p.position.x());
  ASSERT_EQ(xs.size(), 16u);  // 60 / 4 + 1
  std::sort(xs.begin(), xs.end());
  EXPECT_NEAR(xs.front(), 0.0, 1e-9);
  EXPECT_NEAR(xs.back(), 60.0, 1e-9);
  for (std::size_t i = 1; i < xs.size(); ++i) EXPECT_NEAR(xs[i] - xs[i - 1], 4.0, 1e-9);
  // Trees: trunks and crowns, crowns around the configured size and above the trunk height.
  std::size_t crown = 0, trunk = 0;
  for (auto l : f.mesh.labels) {
    crown += l == SurfaceClass::crown;
    trunk += l == SurfaceClass::trunk;
  }
  EXPECT_GT(crown, 16u * 5u * 6u * 20u - 1u);
  EXPECT_GT(trunk, 0u);
  for (const auto& p : f.plants) {
    if (p.kind != PlantKind::tree) continue;
    EXPECT_GT(p.height, c.trunk_height + 0.5 * c.crown_height);
    EXPECT_LT(p.height, c.trunk_height + 2.5 * c.crown_height);
  }
}

TEST(Orchard, MissingTreesAndDeterminism) {
  OrchardConfig c;
  c.rows = 20;
  c.row_length = 100.0;
  c.tree_spacing = 4.0;
  c.missing_trees_percent = 10.0;
  c.weeds = WeedLevel::none;
  const Field f = generate_orchard(c, TerrainConfig{}, 8);
  const double trees = static_cast<double>(std::count_if(
      f.plants.begin(), f.plants.end(), [](const Plant& p) { return p.kind == PlantKind::tree; }));
  EXPECT_NEAR(1.0 - trees / (20.0 * 26.0), 0.10, 0.04);
  const Field g = generate_orchard(c, TerrainConfig{}, 8);
  EXPECT_EQ(f.mesh.vertices, g.mesh.vertices);
  c.row_spacing = 0.0;
  EXPECT_THROW(generate_orchard(c, TerrainConfig{}, 8), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::sim
