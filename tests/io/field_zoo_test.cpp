// Issue 10: the zoo of fields is valid, deterministic per seed and covers the bands.
#include "rownav/sim/field_zoo.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <set>

#include "rownav/io/yaml_config.hpp"

namespace rownav::sim {
namespace {

std::string text(const FieldConfig& c) { return YAML::Dump(io::encode_config(c)); }

TEST(FieldZoo, DeterministicPerSeedAndIndex) {
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(text(zoo_field(i, 7)), text(zoo_field(i, 7)));
    EXPECT_NE(text(zoo_field(i, 7)), text(zoo_field(i, 8)));
  }
  EXPECT_NE(text(zoo_field(0, 7)), text(zoo_field(5, 7)));  // same band, another draw
  EXPECT_THROW(zoo_field(-1, 7), std::invalid_argument);
}

TEST(FieldZoo, HundredFieldsValidAndCoverTheBands) {
  std::set<FieldKind> kinds;
  std::set<OrchardForm> forms;
  std::set<WeedLevel> weeds;
  double lo = 1e9, hi = 0.0, steepest = 0.0;
  int curved = 0, gaps = 0, hedges = 0;
  for (int i = 0; i < 100; ++i) {
    const FieldConfig c = zoo_field(i, 1);
    EXPECT_NO_THROW(c.validate()) << c.name;
    EXPECT_EQ(c.name.rfind("zoo_1_" + std::to_string(i) + "_", 0), 0u);
    kinds.insert(c.kind);
    lo = std::min(lo, nominal_row_spacing(c)), hi = std::max(hi, nominal_row_spacing(c));
    steepest = std::max({steepest, std::abs(c.terrain.slope_x_deg), std::abs(c.terrain.slope_y_deg)});
    curved += c.vineyard.curvature_amplitude + c.orchard.curvature_amplitude +
                  c.row_crop.curvature_amplitude > 0.0;
    gaps += (c.kind == FieldKind::vineyard && c.vineyard.gap_count > 0) ||
            (c.kind == FieldKind::orchard && c.orchard.gap_count > 0);
    hedges += c.kind == FieldKind::vineyard && c.vineyard.canopy_shape == CanopyShape::solid_hedge;
    if (c.kind == FieldKind::orchard) forms.insert(c.orchard.form);
    weeds.insert(c.kind == FieldKind::vineyard ? c.vineyard.weeds
                 : c.kind == FieldKind::orchard ? c.orchard.weeds : c.row_crop.weeds);
  }
  EXPECT_EQ(kinds.size(), 3u);
  EXPECT_EQ(forms.size(), 2u);
  EXPECT_EQ(weeds.size(), 3u);
  EXPECT_LT(lo, 0.6);  // row crops from 0.5 m
  EXPECT_GT(hi, 6.0);  // orchards to 7 m
  const double pct = 100.0 * std::tan(steepest * M_PI / 180.0);
  EXPECT_GT(pct, 12.0);
  EXPECT_LE(pct, 15.0 + 1e-9);
  EXPECT_GT(curved, 15);
  EXPECT_GT(gaps, 30);
  EXPECT_GT(hedges, 5);
  RecordProperty("max_slope_percent", pct);
}

TEST(FieldZoo, FirstBandsGenerate) {
  for (int i = 0; i < kZooBands; ++i) {
    ZooConfig z;
    z.row_length_min = z.row_length_max = 15.0;  // small: fast
    const Field f = generate_field(zoo_field(i, 3, z));
    EXPECT_EQ(static_cast<int>(f.rows.size()), z.rows) << i;
    EXPECT_GT(f.mesh.triangle_count(), 1000u) << i;
    EXPECT_FALSE(f.plants.empty()) << i;
  }
}

TEST(FieldZoo, ReferenceRoundTripsAndRejectsWhatIsNotOne) {
  const ZooRef ref{7, 17};
  const auto back = parse_zoo_ref(zoo_ref_text(ref));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->seed, 7u);
  EXPECT_EQ(back->index, 17);
  EXPECT_EQ(zoo_ref_text(ref), "zoo:7:17");
  for (const char* bad : {"zoo:", "zoo:1", "zoo:1:", "zoo::3", "zoo:1:-2", "zoo:a:1", "zoo:1:2x",
                          "config/fields/zoo:1:2.yaml", "field.yaml", "zoo:1:99999999999"})
    EXPECT_FALSE(parse_zoo_ref(bad)) << bad;
}

TEST(FieldZoo, ConfigValidates) {
  ZooConfig z;
  z.crop_row_max = 0.1;
  EXPECT_THROW(z.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::sim
