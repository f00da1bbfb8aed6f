#include "rownav/sim/vineyard.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "rownav/sim/plant_geometry.hpp"
#include "rownav/sim/ray_caster.hpp"
#include "rownav/sim/row_dressing.hpp"

namespace rownav::sim {
namespace {

TerrainConfig flat() {
  TerrainConfig t;
  t.roughness = 0.0;
  return t;
}

std::vector<const Plant*> of_kind(const Field& f, PlantKind k, int row = -2) {
  std::vector<const Plant*> out;
  for (const auto& p : f.plants)
    if (p.kind == k && (row == -2 || p.row == row)) out.push_back(&p);
  return out;
}

std::size_t count_label(const Field& f, SurfaceClass c) {
  return static_cast<std::size_t>(std::count(f.mesh.labels.begin(), f.mesh.labels.end(), c));
}

/// Fraction of 0.1 m bins along row 0 (y = 0, straight) touched by a canopy triangle.
double canopy_cover(const Field& f, double length) {
  std::vector<bool> bins(static_cast<std::size_t>(length / 0.1), false);
  for (std::size_t i = 0; i < f.mesh.triangles.size(); ++i) {
    if (f.mesh.labels[i] != SurfaceClass::canopy) continue;
    float lo = 1e9f, hi = -1e9f, y = 0.0f;
    for (auto v : f.mesh.triangles[i]) {
      lo = std::min(lo, f.mesh.vertices[v].x());
      hi = std::max(hi, f.mesh.vertices[v].x());
      y += f.mesh.vertices[v].y() / 3.0f;
    }
    if (std::abs(y) > 0.8f) continue;
    for (int b = std::max(0, static_cast<int>(lo / 0.1f));
         b <= std::min(static_cast<int>(bins.size()) - 1, static_cast<int>(hi / 0.1f)); ++b)
      bins[static_cast<std::size_t>(b)] = true;
  }
  return static_cast<double>(std::count(bins.begin(), bins.end(), true)) / bins.size();
}

TEST(Vineyard, RowsAndSpacingAsConfigured) {
  VineyardConfig c;
  c.rows = 7;
  c.row_spacing = 2.8;
  c.row_length = 30.0;
  const Field f = generate_vineyard(c, flat(), 3);
  ASSERT_EQ(f.rows.size(), 7u);
  EXPECT_DOUBLE_EQ(f.row_spacing, 2.8);
  for (std::size_t k = 0; k < f.rows.size(); ++k) {
    EXPECT_EQ(f.rows[k].id, static_cast<int>(k));
    EXPECT_NEAR(f.rows[k].start().y(), 2.8 * k, 1e-9);
    EXPECT_NEAR(f.rows[k].length(), 30.0, 1e-9);
    EXPECT_NEAR(f.rows[k].start().x(), 0.0, 1e-9);
  }
  // Plants lie on their row's line.
  for (const auto& p : f.plants) {
    if (p.kind == PlantKind::weed) continue;
    const PolylinePath path(f.rows[static_cast<std::size_t>(p.row)].polyline);
    ASSERT_LT((path.point(path.project(p.position)) - p.position).norm(), 1e-9);
  }
}

TEST(Vineyard, CurvedRowsKeepTheirSpacing) {
  VineyardConfig c;
  c.rows = 4;
  c.curvature_amplitude = 1.5;
  c.curvature_wavelength = 40.0;
  const Field f = generate_vineyard(c, flat(), 5);
  double max_dev = 0.0;
  for (std::size_t i = 0; i < f.rows[0].polyline.size(); ++i) {
    max_dev = std::max(max_dev, std::abs(f.rows[0].polyline[i].y()));
    EXPECT_NEAR(f.rows[1].polyline[i].y() - f.rows[0].polyline[i].y(), c.row_spacing, 1e-9);
  }
  EXPECT_GT(max_dev, 1.2);  // really bent
}

TEST(Vineyard, MissingPlantsAndGaps) {
  VineyardConfig c;
  c.rows = 20;
  c.row_length = 100.0;
  c.missing_plants_percent = 5.0;
  c.gap_count = 0;
  c.wires = false;
  const Field f = generate_vineyard(c, flat(), 11);
  const double slots = 20.0 * 100.0;  // 1 m spacing, 100 vines a row
  const double missing = 1.0 - of_kind(f, PlantKind::vine).size() / slots;
  EXPECT_NEAR(missing, 0.05, 0.015);

  c.missing_plants_percent = 0.0;
  c.gap_count = 3;
  c.gap_length_plants = 4;
  const Field g = generate_vineyard(c, flat(), 12);
  EXPECT_EQ(of_kind(g, PlantKind::vine).size(), 2000u - 12u);
  int gaps = 0;
  for (int r = 0; r < 20; ++r) {
    auto vines = of_kind(g, PlantKind::vine, r);
    std::sort(vines.begin(), vines.end(),
              [](auto a, auto b) { return a->position.x() < b->position.x(); });
    for (std::size_t i = 1; i < vines.size(); ++i)
      if (std::abs(vines[i]->position.x() - vines[i - 1]->position.x() - 5.0) < 1e-6) ++gaps;
  }
  EXPECT_EQ(gaps, 3);
}

TEST(Vineyard, PostsEveryPostSpacingAndEndPosts) {
  VineyardConfig c;
  c.rows = 3;
  c.row_length = 47.0;
  c.post_spacing = 5.5;
  const Field f = generate_vineyard(c, flat(), 2);
  for (int r = 0; r < 3; ++r) {
    const auto ends = of_kind(f, PlantKind::end_post, r);
    ASSERT_EQ(ends.size(), 2u);
    EXPECT_NEAR(std::min(ends[0]->position.x(), ends[1]->position.x()), 0.0, 1e-9);
    EXPECT_NEAR(std::max(ends[0]->position.x(), ends[1]->position.x()), 47.0, 1e-9);
    EXPECT_GT(ends[0]->radius, of_kind(f, PlantKind::post, r)[0]->radius);
    std::vector<double> xs{0.0, 47.0};
    for (auto* p : of_kind(f, PlantKind::post, r)) xs.push_back(p->position.x());
    std::sort(xs.begin(), xs.end());
    EXPECT_EQ(xs.size(), 10u);  // 47 / 5.5 -> 9 bays
    for (std::size_t i = 1; i < xs.size(); ++i) EXPECT_NEAR(xs[i] - xs[i - 1], 5.5, 0.5);
  }
  EXPECT_GT(count_label(f, SurfaceClass::wire), 0u);
  EXPECT_GT(count_label(f, SurfaceClass::post), 0u);
  EXPECT_GT(count_label(f, SurfaceClass::trunk), 0u);
  EXPECT_GT(count_label(f, SurfaceClass::ground), 0u);
  c.wires = false;
  EXPECT_EQ(count_label(generate_vineyard(c, flat(), 2), SurfaceClass::wire), 0u);
}

TEST(Vineyard, CanopyIsNotABox) {
  VineyardConfig c;
  c.rows = 1;
  c.row_length = 40.0;
  c.stage = GrowthStage::high;
  const Field f = generate_vineyard(c, flat(), 4);
  std::map<int, float> half_width;  // per 0.5 m slice
  for (std::size_t i = 0; i < f.mesh.triangles.size(); ++i) {
    if (f.mesh.labels[i] != SurfaceClass::canopy) continue;
    for (auto v : f.mesh.triangles[i]) {
      const auto& p = f.mesh.vertices[v];
      auto& hw = half_width[static_cast<int>(std::floor(p.x() / 0.5f))];
      hw = std::max(hw, std::abs(p.y()));
    }
  }
  double sum = 0.0, sum2 = 0.0;
  for (const auto& [slice, hw] : half_width) {
    sum += hw;
    sum2 += hw * hw;
  }
  const double n = static_cast<double>(half_width.size());
  const double sd = std::sqrt(sum2 / n - (sum / n) * (sum / n));
  EXPECT_GT(sd, 0.03);
  // Shoots protrude into the inter-row, but no further than half width + protrusion.
  float widest = 0.0f;
  for (const auto& [slice, hw] : half_width) widest = std::max(widest, hw);
  EXPECT_GT(widest, 0.5 * c.canopy_width + 0.1);
  EXPECT_LT(widest, 0.5 * c.canopy_width * 1.5 + c.shoot_protrusion + 0.1);
}

TEST(Vineyard, DensityOrderedByGrowthStage) {
  VineyardConfig c;
  c.rows = 1;
  c.row_length = 30.0;
  c.missing_plants_percent = 0.0;
  c.gap_count = 0;
  std::vector<std::size_t> tris;
  std::vector<double> cover, top;
  for (auto s : {GrowthStage::low, GrowthStage::medium, GrowthStage::high}) {
    c.stage = s;
    const Field f = generate_vineyard(c, flat(), 9);
    tris.push_back(count_label(f, SurfaceClass::canopy));
    cover.push_back(canopy_cover(f, c.row_length));
    double h = 0.0;
    for (auto* p : of_kind(f, PlantKind::vine)) h += p->height;
    top.push_back(h);
  }
  EXPECT_LT(tris[0], tris[1]);
  EXPECT_LT(tris[1], tris[2]);
  EXPECT_LT(cover[0], cover[2]);
  EXPECT_LT(cover[0], 0.95);  // young shoots leave gaps
  EXPECT_GT(cover[2], 0.9);   // a full wall
  EXPECT_LT(top[0], top[1]);
  EXPECT_LT(top[1], top[2]);
}

TEST(Vineyard, MissingVinesLeaveCanopyGaps) {
  VineyardConfig c;
  c.rows = 1;
  c.row_length = 40.0;
  c.gap_count = 1;
  c.gap_length_plants = 3;
  c.stage = GrowthStage::high;
  const Field f = generate_vineyard(c, flat(), 21);
  EXPECT_LT(canopy_cover(f, c.row_length), 0.97);
}

TEST(Vineyard, WeedCountOrdered) {
  VineyardConfig c;
  c.rows = 4;
  c.row_length = 40.0;
  std::vector<std::size_t> n;
  for (auto w : {WeedLevel::none, WeedLevel::some, WeedLevel::many}) {
    c.weeds = w;
    const Field f = generate_vineyard(c, flat(), 6);
    n.push_back(of_kind(f, PlantKind::weed).size());
    for (auto* p : of_kind(f, PlantKind::weed)) {
      EXPECT_EQ(p->row, -1);
      // Between rows 0 and 3, clear of the canopy line.
      EXPECT_GT(p->position.y(), 0.2);
      EXPECT_LT(p->position.y(), 3 * c.row_spacing - 0.2);
    }
  }
  EXPECT_EQ(n[0], 0u);
  EXPECT_LT(n[0], n[1]);
  EXPECT_LT(3 * n[1], n[2]);
}

TEST(Vineyard, DeterministicUnderTheSeed) {
  VineyardConfig c;
  c.rows = 3;
  c.row_length = 20.0;
  c.weeds = WeedLevel::some;
  TerrainConfig t;
  t.roughness = 0.05;
  const Field a = generate_vineyard(c, t, 42), b = generate_vineyard(c, t, 42);
  const Field d = generate_vineyard(c, t, 43);
  ASSERT_EQ(a.mesh.vertices.size(), b.mesh.vertices.size());
  EXPECT_TRUE(std::equal(a.mesh.vertices.begin(), a.mesh.vertices.end(), b.mesh.vertices.begin()));
  EXPECT_EQ(a.plants.size(), b.plants.size());
  EXPECT_FALSE(a.mesh.vertices.size() == d.mesh.vertices.size() &&
               std::equal(a.mesh.vertices.begin(), a.mesh.vertices.end(), d.mesh.vertices.begin()));
}

TEST(Vineyard, TriangleBudgetOfALargeHighCanopyVineyard) {
  VineyardConfig c;
  c.rows = 20;
  c.row_length = 100.0;
  c.stage = GrowthStage::high;
  c.weeds = WeedLevel::many;
  const Field f = generate_vineyard(c, TerrainConfig{}, 1);
  std::printf("20 x 100 m high canopy, many weeds: %zu triangles\n", f.mesh.triangle_count());
  EXPECT_GT(f.mesh.triangle_count(), 200000u);
  EXPECT_LT(f.mesh.triangle_count(), 800000u);
  EXPECT_EQ(f.mesh.labels.size(), f.mesh.triangle_count());
}

TEST(RowDressing, GroundCoversHeadlandsAndIsCoarsenedOverBudget) {
  Field f;
  TerrainConfig t;
  t.cell_size = 0.5;
  f.terrain = Terrain(t);
  f.headland_width = 5.0;
  f.rows.push_back({0, 0, {{0.0, 0.0}, {100.0, 0.0}}, 0.3, 1.8});
  f.rows.push_back({1, 0, {{0.0, 20.0}, {100.0, 20.0}}, 0.3, 1.8});
  add_ground(f);
  EXPECT_EQ(f.mesh.triangle_count(), 2u * 220u * 60u);  // 110 x 30 m at 0.5 m
  EXPECT_NEAR(f.mesh.bounds().min().x(), -5.0f, 1e-4f);
  EXPECT_NEAR(f.mesh.bounds().max().y(), 25.0f, 1e-4f);
  Field g = f;
  g.mesh = TriangleMesh{};
  add_ground(g, 1000);
  EXPECT_LE(g.mesh.triangle_count(), 1100u);
  EXPECT_GT(g.mesh.triangle_count(), 500u);
}

TEST(Vineyard, ValidateNamesTheField) {
  VineyardConfig c;
  c.rows = 0;
  EXPECT_THROW(generate_vineyard(c, flat(), 1), std::invalid_argument);
  try {
    c.validate();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("rows:", 0), 0u);
  }
  c = VineyardConfig{};
  c.cordon_height_max = 0.1;  // below the minimum
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

TEST(Vineyard, SolidHedgeIsAContinuousMoundFromTheGround) {
  // Issue 10: a real photogrammetric vineyard is a continuous mound, no trunk zone visible.
  VineyardConfig c;
  c.rows = 3;
  c.row_length = 12.0;
  c.row_spacing = 1.75;
  c.canopy_width = 0.6;
  c.canopy_top = 1.8;
  c.canopy_shape = CanopyShape::solid_hedge;
  c.missing_plants_percent = 0.0;
  c.gap_count = 0;
  c.wires = false;
  const Field f = generate_vineyard(c, flat(), 5);
  EXPECT_EQ(count_label(f, SurfaceClass::trunk), 0u);
  const RayCaster world(f.mesh);
  // Horizontal rays from the middle of corridor 0 towards row 1 (at y = 1.75): every height from
  // just above the ground to near the top hits the canopy, the face nearer the row centre the
  // higher it is (a mound), within the roughness of the configured width.
  double previous = 0.0;
  for (double z = 0.1; z < 1.6; z += 0.25) {
    for (double x = 2.0; x < 10.0; x += 0.7) {
      const RayHit h = world.cast({float(x), 0.875f, float(z)}, {0.0f, 1.0f, 0.0f}, 0.0f, 2.0f);
      ASSERT_TRUE(std::isfinite(h.distance)) << "gap at x " << x << ", z " << z;
      EXPECT_EQ(h.label, SurfaceClass::canopy);
      const double depth = 0.875 + h.distance - (1.75 - 0.5 * c.canopy_width);  // behind the foot
      EXPECT_GT(depth, -0.1 * c.canopy_width) << "x " << x << ", z " << z;
      EXPECT_LT(depth, 0.5 * c.canopy_width) << "x " << x << ", z " << z;
    }
    const RayHit h = world.cast({6.0f, 0.875f, float(z)}, {0.0f, 1.0f, 0.0f}, 0.0f, 2.0f);
    EXPECT_GT(h.distance, previous - 0.1) << "z " << z;
    previous = h.distance;
  }
  // Nothing above the top (+5 % vigour), the posts hidden inside.
  const RayHit above = world.cast({6.0f, 0.875f, 1.95f}, {0.0f, 1.0f, 0.0f}, 0.0f, 2.0f);
  EXPECT_FALSE(std::isfinite(above.distance) && above.label == SurfaceClass::canopy);
}

}  // namespace
}  // namespace rownav::sim
