#include "rownav/sim/row_crop.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace rownav::sim {
namespace {

TEST(RowCrop, PresetsWithinTheSpecRanges) {
  for (auto crop : {CropType::maize, CropType::cabbage, CropType::leek}) {
    const CropPreset p = crop_preset(crop);
    EXPECT_GE(p.plant_height, 0.2);
    EXPECT_LE(p.plant_height, 0.6);
    EXPECT_GE(p.plant_spacing, 0.13);
    EXPECT_LE(p.plant_spacing, 0.5);
    EXPECT_GE(p.row_spacing, 0.5);
    EXPECT_LE(p.row_spacing, 0.9);
  }
  RowCropConfig c;
  c.crop = CropType::cabbage;
  c.row_spacing = 0.8;
  EXPECT_DOUBLE_EQ(c.resolved().row_spacing, 0.8);
  EXPECT_DOUBLE_EQ(c.resolved().plant_spacing, crop_preset(CropType::cabbage).plant_spacing);
}

class RowCropPerCrop : public ::testing::TestWithParam<CropType> {};

TEST_P(RowCropPerCrop, SpacingHeightAndLabels) {
  RowCropConfig c;
  c.crop = GetParam();
  c.rows = 6;
  c.row_length = 20.0;
  c.missing_plants_percent = 0.0;
  const CropPreset p = c.resolved();
  const Field f = generate_row_crop(c, TerrainConfig{}, 5);
  ASSERT_EQ(f.rows.size(), 6u);
  EXPECT_DOUBLE_EQ(f.row_spacing, p.row_spacing);
  for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(f.rows[k].start().y(), p.row_spacing * k, 1e-9);
  std::vector<double> xs;
  double height = 0.0;
  for (const auto& pl : f.plants) {
    if (pl.kind != PlantKind::crop) continue;
    height += pl.height;
    if (pl.row == 1) {
      xs.push_back(pl.position.x());
      EXPECT_NEAR(pl.position.y(), p.row_spacing, 5 * c.position_noise);
    }
  }
  std::sort(xs.begin(), xs.end());
  const double mean_gap = (xs.back() - xs.front()) / static_cast<double>(xs.size() - 1);
  EXPECT_NEAR(mean_gap, p.plant_spacing, 0.1 * p.plant_spacing);
  EXPECT_NEAR(height / (6.0 * static_cast<double>(xs.size())), p.plant_height,
              0.1 * p.plant_height);
  const auto crop_tris = std::count(f.mesh.labels.begin(), f.mesh.labels.end(), SurfaceClass::crop);
  EXPECT_GT(crop_tris, static_cast<long>(6 * xs.size() * 8));
  // The crop stays low: no crop vertex above 1.6 x the nominal height.
  for (std::size_t i = 0; i < f.mesh.triangles.size(); ++i)
    if (f.mesh.labels[i] == SurfaceClass::crop) {
      ASSERT_LT(f.mesh.vertices[f.mesh.triangles[i][0]].z(), 1.6 * p.plant_height + 0.05);
    }
}

INSTANTIATE_TEST_SUITE_P(Crops, RowCropPerCrop,
                         ::testing::Values(CropType::maize, CropType::cabbage, CropType::leek));

TEST(RowCrop, InvalidConfigNamesTheField) {
  RowCropConfig c;
  c.rows = 0;
  try {
    generate_row_crop(c, TerrainConfig{}, 1);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rows"), std::string::npos);
  }
}

}  // namespace
}  // namespace rownav::sim

namespace rownav::sim {
namespace {

TEST(RowCrop, WeedSizesFollowTheConfigAndDefaultsKeepTheLevelPreset) {
  RowCropConfig c;
  c.crop = CropType::cabbage;
  c.rows = 3;
  c.row_length = 30.0;
  c.weeds = WeedLevel::many;
  const auto weeds = [](const Field& f) {
    std::vector<Plant> w;
    for (const auto& p : f.plants)
      if (p.kind == PlantKind::weed) w.push_back(p);
    return w;
  };
  const Field preset = generate_row_crop(c, TerrainConfig{}, 4);
  c.weed_max_height = 0.3;
  c.weed_max_radius = 0.1;
  const Field sized = generate_row_crop(c, TerrainConfig{}, 4);
  const auto a = weeds(preset), b = weeds(sized);
  ASSERT_GT(a.size(), 10u);
  ASSERT_EQ(a.size(), b.size());  // same draws, other sizes
  double tallest_a = 0.0, widest_a = 0.0;
  for (const auto& p : a) tallest_a = std::max(tallest_a, p.height), widest_a = std::max(widest_a, p.radius);
  for (const auto& p : b) {
    EXPECT_LE(p.height, 0.3 + 1e-9);
    EXPECT_LE(p.radius, 0.1 + 1e-9);
  }
  EXPECT_GT(tallest_a, 0.3);  // the vineyard-sized preset: up to 0.5 m
  EXPECT_GT(widest_a, 0.1);
  c.weed_max_height = -1.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::sim
