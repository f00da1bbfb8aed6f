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

namespace rownav::sim {
namespace {

int trees(const Field& f) {
  return static_cast<int>(std::count_if(f.plants.begin(), f.plants.end(),
                                        [](const Plant& p) { return p.kind == PlantKind::tree; }));
}

TEST(OrchardIssue10, GapsJitterTrunksAndHedgerows) {
  OrchardConfig c;
  c.rows = 3, c.row_length = 40.0, c.tree_spacing = 2.0, c.missing_trees_percent = 0.0;
  const int full = trees(generate_orchard(c, TerrainConfig{}, 5));
  EXPECT_EQ(full, 3 * 21);
  c.gap_count = 1, c.gap_length_trees = 8;  // a 18 m gap
  const Field gapped = generate_orchard(c, TerrainConfig{}, 5);
  EXPECT_EQ(trees(gapped), full - 8);
  double longest = 0.0;
  for (int r = 0; r < 3; ++r) {
    std::vector<double> xs;
    for (const auto& p : gapped.plants)
      if (p.kind == PlantKind::tree && p.row == r) xs.push_back(p.position.x());
    std::sort(xs.begin(), xs.end());
    for (std::size_t i = 1; i < xs.size(); ++i) longest = std::max(longest, xs[i] - xs[i - 1]);
  }
  EXPECT_NEAR(longest, 18.0, 1e-6);
  c.gap_count = 0, c.position_jitter = 0.3, c.trunk_variation = 0.3, c.trunk_diameter = 0.2;
  const Field jittered = generate_orchard(c, TerrainConfig{}, 5);
  double max_off = 0.0, rmin = 1.0, rmax = 0.0;
  for (const auto& p : jittered.plants) {
    if (p.kind != PlantKind::tree) continue;
    max_off = std::max(max_off, std::abs(p.position.y() - jittered.rows[p.row].polyline[0].y()));
    rmin = std::min(rmin, p.radius), rmax = std::max(rmax, p.radius);
  }
  EXPECT_GT(max_off, 0.2);
  EXPECT_LT(max_off, 1.5);
  EXPECT_LT(rmin, 0.09);  // trunks 0.1-0.3 m
  EXPECT_GT(rmax, 0.11);
  // A hedgerow's crowns along the row are wider than across it (a fruit wall).
  c.position_jitter = 0.0, c.trunk_variation = 0.0, c.form = OrchardForm::hedgerow;
  c.crown_diameter = 1.2, c.tree_spacing = 1.5;
  const Field hedge = generate_orchard(c, TerrainConfig{.roughness = 0.0}, 5);
  Eigen::AlignedBox3f box;
  for (std::size_t i = 0; i < hedge.mesh.triangles.size(); ++i)
    if (hedge.mesh.labels[i] == SurfaceClass::crown)
      for (auto v : hedge.mesh.triangles[i])
        if (std::abs(hedge.mesh.vertices[v].y()) < 2.0) box.extend(hedge.mesh.vertices[v]);
  EXPECT_GT(box.sizes().x(), 39.0);
  EXPECT_LT(box.sizes().y(), 2.5);
  c.form = OrchardForm::free_standing, c.hedge_overlap = 0.1;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::sim
