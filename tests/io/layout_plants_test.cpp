// Issue 10: imported layouts place any plant kind with geometry (trees with per-plant trunk and
// crown sizes, crop plants, posts) from CSV columns / GeoJSON properties; dressing none.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "rownav/io/field_builder.hpp"
#include "rownav/io/layout_reader.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

fs::path write(const std::string& name, const std::string& text) {
  const fs::path p = fs::path(::testing::TempDir()) / name;
  std::ofstream(p) << text;
  return p;
}

std::size_t count(const sim::Field& f, sim::SurfaceClass c) {
  return static_cast<std::size_t>(std::count(f.mesh.labels.begin(), f.mesh.labels.end(), c));
}

/// Trunk triangles within `r` of (x, y): the trunk of the tree there.
float trunk_radius_at(const sim::Field& f, double x, double y) {
  float r = 0.0f;
  for (std::size_t i = 0; i < f.mesh.triangles.size(); ++i) {
    if (f.mesh.labels[i] != sim::SurfaceClass::trunk) continue;
    for (const auto v : f.mesh.triangles[i]) {
      const Eigen::Vector3f& p = f.mesh.vertices[v];
      const float d = std::hypot(p.x() - static_cast<float>(x), p.y() - static_cast<float>(y));
      if (d < 1.0f) r = std::max(r, d);
    }
  }
  return r;
}

sim::FieldConfig layout_config(const fs::path& file) {
  sim::FieldConfig c;
  c.kind = sim::FieldKind::layout;
  c.name = "trees";
  c.layout.file = file.string();
  c.vineyard.weeds = sim::WeedLevel::none;
  return c;
}

TEST(LayoutPlants, CsvTreesWithTheirOwnTrunkAndCrown) {
  const fs::path csv = write("rownav_trees.csv",
                             "kind,row,x,y,trunk_diameter,crown_diameter,crown_height\n"
                             "row,1,0,0,,,\nrow,1,12,0,,,\nrow,2,0,5,,,\nrow,2,12,5,,,\n"
                             "tree,1,0,0,0.3,4.0,3.0\ntree,1,6,0,,,\ntree,1,12,0,0.1,1.0,1.0\n"
                             "tree,2,0,5,,,\ntree,2,12,5,0.2,,\npost,2,6,5,,,\n");
  const sim::Field f = build_field(layout_config(csv), fs::temp_directory_path());
  ASSERT_EQ(f.plants.size(), 6u);
  EXPECT_EQ(f.plants[0].kind, sim::PlantKind::tree);
  EXPECT_DOUBLE_EQ(f.plants[0].radius, 0.15);
  EXPECT_DOUBLE_EQ(f.plants[1].radius, 0.5 * sim::OrchardConfig{}.trunk_diameter);  // default
  EXPECT_DOUBLE_EQ(f.plants[2].radius, 0.05);
  EXPECT_GT(f.plants[0].height, f.plants[2].height + 1.0);  // 3 m crown vs 1 m
  EXPECT_NEAR(trunk_radius_at(f, 0, 0), 0.15f, 1e-3f);
  EXPECT_NEAR(trunk_radius_at(f, 12, 0), 0.05f, 1e-3f);
  EXPECT_GT(count(f, sim::SurfaceClass::crown), 100u);
  EXPECT_GT(count(f, sim::SurfaceClass::post), 0u);
  EXPECT_EQ(count(f, sim::SurfaceClass::canopy), 0u);  // trees, not vines
  EXPECT_GT(f.rows[0].half_width, 0.5);                // the rows take the crowns' width
}

TEST(LayoutPlants, GeoJsonTreesAndCropsWithProperties) {
  const fs::path gj = write(
      "rownav_crops.geojson",
      R"({"type":"FeatureCollection","features":[
  {"type":"Feature","properties":{"type":"row"},"geometry":{"type":"LineString",
   "coordinates":[[-0.97747,51.59721],[-0.97700,51.59721]]}},
  {"type":"Feature","properties":{"type":"row"},"geometry":{"type":"LineString",
   "coordinates":[[-0.97747,51.59725],[-0.97700,51.59725]]}},
  {"type":"Feature","properties":{"kind":"tree","trunk_diameter":0.25,"crown_diameter":3.5},
   "geometry":{"type":"Point","coordinates":[-0.97740,51.59721]}},
  {"type":"Feature","properties":{"kind":"crop","height":0.9,"width":0.4},
   "geometry":{"type":"Point","coordinates":[-0.97720,51.59725]}}]})");
  const sim::RowLayout layout = read_layout(gj);
  ASSERT_EQ(layout.shapes.size(), 2u);
  EXPECT_DOUBLE_EQ(layout.shapes[0].trunk_diameter, 0.25);
  EXPECT_TRUE(std::isnan(layout.shapes[0].trunk_height));
  const sim::Field f = build_field(layout_config(gj), fs::temp_directory_path());
  ASSERT_EQ(f.plants.size(), 2u);
  EXPECT_DOUBLE_EQ(f.plants[0].radius, 0.125);
  EXPECT_DOUBLE_EQ(f.plants[1].height, 0.9);
  EXPECT_GT(count(f, sim::SurfaceClass::crop), 0u);
  EXPECT_THROW(read_layout(write("rownav_bad.geojson",
                                 R"({"type":"FeatureCollection","features":[
  {"type":"Feature","properties":{},"geometry":{"type":"LineString",
   "coordinates":[[-0.97747,51.59721],[-0.97700,51.59721]]}},
  {"type":"Feature","properties":{"kind":"tree","crown_diameter":-1},
   "geometry":{"type":"Point","coordinates":[-0.97740,51.59721]}}]})")),
               InputError);
}

TEST(LayoutPlants, DressingNoneLeavesTheMeshUndressed) {
  const fs::path csv = write("rownav_none.csv", "row,x,y\n1,0,0\n1,10,0\n2,0,2\n2,10,2\n");
  const fs::path obj = write("rownav_none.obj",
                             "v -20 -20 0\nv 30 -20 0\nv 30 20 0\nv -20 20 0\nf 1 2 3 4\n");
  sim::FieldConfig c = layout_config(csv);
  c.layout.terrain_mesh = obj.string();
  c.layout.dressing = sim::LayoutDressing::none;
  const sim::Field f = build_field(c, fs::temp_directory_path());
  EXPECT_EQ(f.mesh.triangle_count(), 2u);  // the mesh alone
  EXPECT_TRUE(f.plants.empty());
  EXPECT_EQ(f.rows.size(), 2u);
  c.layout.dressing = sim::LayoutDressing::plants;
  EXPECT_GT(build_field(c, fs::temp_directory_path()).mesh.triangle_count(), 1000u);
}

TEST(LayoutPlants, UnknownCsvColumnStillRejected) {
  const fs::path csv = write("rownav_col.csv", "row,x,y,girth\n1,0,0,1\n1,5,0,1\n");
  EXPECT_THROW(read_layout(csv), InputError);
}

}  // namespace
}  // namespace rownav::io
