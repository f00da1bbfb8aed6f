#include "rownav/io/field_builder.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace rownav::io {
namespace {

const std::filesystem::path kConfigDir = std::filesystem::path(ROWNAV_SOURCE_DIR) / "config/fields";
const std::filesystem::path kShared(ROWNAV_SHARED_DATA);

// ---- a minimal strict YAML -> Config reader, to check the example files' keys -------------
template <class T>
void read_yaml(const YAML::Node& n, T& v, const std::string& path);

struct YamlVisitor {
  const YAML::Node& node;
  std::string prefix;
  std::set<std::string> seen;
  template <class T>
  void operator()(std::string_view name, T& value) {
    const YAML::Node n = node[std::string(name)];
    if (!n) return;
    seen.emplace(name);
    read_yaml(n, value, prefix + std::string(name));
  }
};

template <class T>
void read_yaml(const YAML::Node& n, T& v, const std::string& path) {
  if constexpr (core::HasFields<T>) {
    ASSERT_TRUE(n.IsMap()) << path;
    YamlVisitor visitor{n, path.empty() ? "" : path + ".", {}};
    T::fields(v, visitor);
    for (const auto& kv : n)
      EXPECT_TRUE(visitor.seen.contains(kv.first.as<std::string>()))
          << "unknown key " << path << "." << kv.first.as<std::string>();
  } else if constexpr (core::NamedEnum<T>) {
    EXPECT_TRUE(core::enum_from_name(n.as<std::string>(), v)) << path;
  } else {
    v = n.as<T>();
  }
}

sim::FieldConfig load(const std::string& file) {
  sim::FieldConfig c;
  read_yaml(YAML::LoadFile((kConfigDir / file).string()), c, "");
  return c;
}

/// Every leaf as "path=value", to compare configs.
struct Dumper {
  std::string prefix;
  std::vector<std::string> out;
  template <class T>
  void operator()(std::string_view name, const T& v) {
    const std::string path = prefix + std::string(name);
    if constexpr (core::HasFields<T>) {
      Dumper d{path + ".", {}};
      T::fields(v, d);
      out.insert(out.end(), d.out.begin(), d.out.end());
    } else if constexpr (core::NamedEnum<T>) {
      out.push_back(path + "=" + std::string(core::enum_name(v)));
    } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
      std::string s;
      for (const auto& e : v) s += e + ";";
      out.push_back(path + "=" + s);
    } else {
      std::ostringstream s;
      s << v;
      out.push_back(path + "=" + s.str());
    }
  }
};

std::vector<std::string> dump(const sim::FieldConfig& c) {
  Dumper d;
  sim::FieldConfig::fields(c, d);
  return d.out;
}

// ---- the example configs, written in C++ (no YAML) ----------------------------------------
sim::FieldConfig narrow_high() {
  sim::FieldConfig c;
  c.kind = sim::FieldKind::vineyard;
  c.name = "vineyard_narrow_high";
  c.seed = 7;
  auto& v = c.vineyard;
  v.rows = 12, v.row_length = 80.0, v.row_spacing = 1.7, v.plant_spacing = 0.9;
  v.cordon_height_min = 0.4, v.cordon_height_max = 0.6, v.stage = sim::GrowthStage::high;
  v.missing_plants_percent = 3.0, v.gap_count = 2, v.gap_length_plants = 3;
  v.curvature_amplitude = 0.4, v.curvature_wavelength = 90.0, v.weeds = sim::WeedLevel::some;
  c.terrain.slope_x_deg = 2.0, c.terrain.slope_y_deg = 1.0, c.terrain.roughness = 0.03;
  c.terrain.seed = 7;
  return c;
}

sim::FieldConfig wide_low() {
  sim::FieldConfig c;
  c.name = "vineyard_wide_low";
  c.seed = 3;
  auto& v = c.vineyard;
  v.rows = 10, v.row_length = 60.0, v.row_spacing = 2.8, v.plant_spacing = 1.2;
  v.cordon_height_min = 0.3, v.cordon_height_max = 0.5, v.canopy_top = 1.6, v.canopy_width = 0.45;
  v.stage = sim::GrowthStage::low, v.shoot_protrusion = 0.2, v.post_spacing = 6.0, v.wires = false;
  v.missing_plants_percent = 8.0, v.gap_count = 3, v.gap_length_plants = 4;
  v.headland_width = 8.0, v.weeds = sim::WeedLevel::many;
  c.terrain.slope_y_deg = 4.0, c.terrain.roughness = 0.05, c.terrain.roughness_wavelength = 3.0;
  c.terrain.seed = 3;
  return c;
}

sim::FieldConfig orchard() {
  sim::FieldConfig c;
  c.kind = sim::FieldKind::orchard;
  c.name = "orchard";
  c.seed = 11;
  c.orchard.weeds = sim::WeedLevel::some;
  c.terrain.roughness = 0.04, c.terrain.seed = 11;
  return c;
}

sim::FieldConfig maize() {
  sim::FieldConfig c;
  c.kind = sim::FieldKind::row_crop;
  c.name = "maize";
  c.seed = 5;
  c.row_crop.crop = sim::CropType::maize;
  c.row_crop.rows = 12, c.row_crop.row_length = 40.0, c.row_crop.weeds = sim::WeedLevel::some;
  c.terrain.roughness = 0.02, c.terrain.seed = 5;
  return c;
}

sim::FieldConfig jojos_block() {
  sim::FieldConfig c;
  c.kind = sim::FieldKind::layout;
  c.name = "jojos_block";
  c.seed = 2;
  c.layout.file = "../../../shared/data/layouts/agrids_jojos_vineyard/jojos_vineyard.geojson";
  c.layout.blocks = {"2019-a-3"};
  auto& v = c.vineyard;
  v.plant_spacing = 1.2, v.stage = sim::GrowthStage::medium, v.canopy_width = 0.45;
  v.post_spacing = 6.0, v.gap_count = 2, v.headland_width = 8.0, v.weeds = sim::WeedLevel::some;
  c.terrain.roughness = 0.03, c.terrain.seed = 2;
  return c;
}

// jojos_block's relative path from config/fields/ reaches ROWNAV_SHARED_DATA (=
// source/../shared/data).
std::filesystem::path layout_base() {
  return kConfigDir;
}

TEST(FieldConfigFiles, YamlKeysAreFieldNamesAndMatchTheCppConfigs) {
  const std::map<std::string, sim::FieldConfig> expected{
      {"vineyard_narrow_high.yaml", narrow_high()},
      {"vineyard_wide_low.yaml", wide_low()},
      {"orchard.yaml", orchard()},
      {"maize.yaml", maize()},
      {"jojos_block.yaml", jojos_block()}};
  for (const auto& [file, cpp] : expected) {
    SCOPED_TRACE(file);
    const sim::FieldConfig y = load(file);
    EXPECT_NO_THROW(y.validate());
    EXPECT_EQ(dump(y), dump(cpp));
  }
}

std::size_t count(const sim::Field& f, sim::PlantKind k) {
  return static_cast<std::size_t>(std::count_if(f.plants.begin(), f.plants.end(),
                                                [k](const sim::Plant& p) { return p.kind == k; }));
}
std::size_t count(const sim::Field& f, sim::SurfaceClass c) {
  return static_cast<std::size_t>(std::count(f.mesh.labels.begin(), f.mesh.labels.end(), c));
}

TEST(BuildField, ProceduralExampleConfigs) {
  const sim::Field a = build_field(narrow_high(), kConfigDir);
  EXPECT_EQ(a.name, "vineyard_narrow_high");
  EXPECT_EQ(a.rows.size(), 12u);
  EXPECT_DOUBLE_EQ(a.row_spacing, 1.7);
  EXPECT_EQ(count(a, sim::PlantKind::end_post), 24u);
  const sim::Field b = build_field(wide_low(), kConfigDir);
  EXPECT_EQ(b.rows.size(), 10u);
  EXPECT_EQ(count(b, sim::SurfaceClass::wire), 0u);
  EXPECT_GT(count(b, sim::PlantKind::weed), count(a, sim::PlantKind::weed));
  const sim::Field o = build_field(orchard(), kConfigDir);
  EXPECT_EQ(o.kind, sim::FieldKind::orchard);
  EXPECT_GT(count(o, sim::PlantKind::tree), 6u * 16u * 9u / 10u);  // 3 % missing
  const sim::Field m = build_field(maize(), kConfigDir);
  EXPECT_EQ(m.kind, sim::FieldKind::row_crop);
  EXPECT_DOUBLE_EQ(m.row_spacing, 0.75);
  std::printf("triangles: narrow_high %zu, wide_low %zu, orchard %zu, maize %zu\n",
              a.mesh.triangle_count(), b.mesh.triangle_count(), o.mesh.triangle_count(),
              m.mesh.triangle_count());
}

TEST(BuildField, JojosBlockFromTheRealLayout) {
  const sim::Field f = build_field(jojos_block(), layout_base());
  EXPECT_EQ(f.kind, sim::FieldKind::layout);
  ASSERT_EQ(f.rows.size(), 23u);
  EXPECT_GT(f.row_spacing, 2.2);
  EXPECT_LT(f.row_spacing, 2.6);
  EXPECT_EQ(count(f, sim::PlantKind::end_post), 46u);
  EXPECT_GT(count(f, sim::PlantKind::vine), 500u);
  EXPECT_GT(count(f, sim::SurfaceClass::ground), 1000u);
  EXPECT_GT(count(f, sim::SurfaceClass::canopy), 10000u);
  std::printf("jojos block 2019-a-3: %zu vines, %zu triangles\n", count(f, sim::PlantKind::vine),
              f.mesh.triangle_count());
}

TEST(BuildField, InstanceAndTerrainMeshes) {
  sim::FieldConfig c = jojos_block();
  c.layout.blocks = {"2109-a-10"};  // 3 rows
  c.layout.instance_mesh = (kShared / "meshes/romea_vine/vine.stl").string();
  const auto ground = std::filesystem::path(::testing::TempDir()) / "rownav_ground.obj";
  std::ofstream(ground) << "v -500 -500 0\nv 500 -500 0\nv 500 500 0\nv -500 500 0\nf 1 2 3 4\n";
  c.layout.terrain_mesh = ground.string();
  const sim::Field f = build_field(c, layout_base());
  ASSERT_EQ(f.rows.size(), 3u);
  EXPECT_EQ(count(f, sim::SurfaceClass::ground), 2u);  // the imported terrain only
  std::size_t instances = 0;
  for (const auto& r : f.rows) instances += static_cast<std::size_t>((r.length() + 2.55) / 5.1);
  EXPECT_EQ(count(f, sim::SurfaceClass::canopy), instances * 10082u);
  EXPECT_EQ(count(f, sim::SurfaceClass::trunk), 0u);  // no procedural vines
}

TEST(BuildField, BadInput) {
  sim::FieldConfig c = narrow_high();
  c.vineyard.rows = 0;
  try {
    build_field(c, kConfigDir);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("vineyard.rows:", 0), 0u) << e.what();
  }
  sim::FieldConfig l = jojos_block();
  EXPECT_THROW(sim::generate_field(l), std::invalid_argument);
  l.layout.file = "missing.geojson";
  EXPECT_THROW(build_field(l, kConfigDir), InputError);
  l.layout.file.clear();
  EXPECT_THROW(build_field(l, kConfigDir), std::invalid_argument);
  l = jojos_block();
  l.layout.instance_mesh = "missing.stl";
  EXPECT_THROW(build_field(l, layout_base()), InputError);
}

}  // namespace
}  // namespace rownav::io
