#include "rownav/io/mesh_reader.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "rownav/sim/row_dressing.hpp"

namespace rownav::io {
namespace {

const std::filesystem::path kVine =
    std::filesystem::path(ROWNAV_SHARED_DATA) / "meshes/romea_vine/vine.stl";

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::path(::testing::TempDir()) / ("rownav_mesh_" + name);
  std::ofstream(p) << text;
  return p;
}

TEST(MeshReader, RomeaVineStl) {
  const sim::TriangleMesh m = read_mesh(kVine, sim::SurfaceClass::canopy);
  EXPECT_EQ(m.triangle_count(), 10082u);
  EXPECT_EQ(m.labels.size(), 10082u);
  EXPECT_EQ(m.labels.front(), sim::SurfaceClass::canopy);
  const auto b = m.bounds();  // README: x -0.26..0.27, y -0.10..5.09, z -0.06..1.58
  EXPECT_NEAR(b.min().x(), -0.26, 0.01);
  EXPECT_NEAR(b.max().x(), 0.27, 0.01);
  EXPECT_NEAR(b.min().y(), -0.10, 0.01);
  EXPECT_NEAR(b.max().y(), 5.09, 0.01);
  EXPECT_NEAR(b.min().z(), -0.06, 0.01);
  EXPECT_NEAR(b.max().z(), 1.58, 0.01);
  for (const auto& t : m.triangles)
    for (auto i : t) ASSERT_LT(i, m.vertices.size());
}

TEST(MeshReader, ObjQuadsAreTriangulated) {
  const auto f = write_temp("quad.obj",
                            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\n"
                            "f 1 2 3 4\nf 1 2 6 5\n");
  const sim::TriangleMesh m = read_mesh(f, sim::SurfaceClass::ground);
  EXPECT_EQ(m.triangle_count(), 4u);
  EXPECT_NEAR(m.bounds().max().z(), 1.0f, 1e-6);
}

TEST(MeshReader, BadFilesThrowInputError) {
  EXPECT_THROW(read_mesh("/nonexistent/vine.stl", sim::SurfaceClass::canopy), InputError);
  // Vertices but no face: zero triangles.
  const auto empty = write_temp("empty.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\n");
  try {
    read_mesh(empty, sim::SurfaceClass::canopy);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), empty.string());
  }
  EXPECT_THROW(read_mesh(write_temp("junk.stl", "this is not a mesh"), sim::SurfaceClass::canopy),
               InputError);
}

/// A one-quad Collada terrain whose position accessor has `stride` (3 = valid).
std::string collada_quad(const std::string& stride) {
  return "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
         "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
         "<library_geometries><geometry id=\"g\"><mesh>\n"
         "<source id=\"p\"><float_array id=\"pa\" count=\"12\">-10 -10 0 40 -10 0 40 20 0 -10 "
         "20 0</float_array>\n"
         "<technique_common><accessor source=\"#pa\" count=\"4\" stride=\"" +
         stride +
         "\"><param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/><param "
         "name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
         "<vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
         "<triangles count=\"2\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>"
         "<p>0 1 2 0 2 3</p></triangles>\n"
         "</mesh></geometry></library_geometries>\n"
         "<library_visual_scenes><visual_scene id=\"s\"><node id=\"n\"><instance_geometry "
         "url=\"#g\"/></node></visual_scene></library_visual_scenes>\n"
         "<scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n";
}

TEST(MeshReader, ColladaAccessorsMustStayInsideTheirArrays) {
  const sim::TriangleMesh m =
      read_mesh(write_temp("quad.dae", collada_quad("3")), sim::SurfaceClass::ground);
  EXPECT_EQ(m.triangle_count(), 2u);
  // assimp 5 reads a huge stride far past the array (SIGSEGV): refused before it sees the file.
  for (const char* stride : {"4", "65536", "4294967295", "999999999999", "-1"}) {
    try {
      read_mesh(write_temp("stride.dae", collada_quad(stride)), sim::SurfaceClass::ground);
      ADD_FAILURE() << stride;
    } catch (const InputError& e) {
      EXPECT_EQ(e.position(), "5:19") << e.what();
      EXPECT_NE(std::string(e.what()).find("stride"), std::string::npos) << e.what();
    }
  }
}

// Found by mesh_fuzz (issue 13): assimp 5 loops on a non-digit in an index list, appending
// indices until memory runs out (800 MB); refused with its position first.
TEST(MeshReader, ColladaIndexListsHoldOnlyIndices) {
  std::string dae = collada_quad("3");
  dae.replace(dae.find("<p>0 1 2"), 8, "<p>0!1 2");
  try {
    read_mesh(write_temp("bang.dae", dae), sim::SurfaceClass::ground);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.position(), "7:75") << e.what();
    EXPECT_NE(std::string(e.what()).find("<p> holds '!', not an index"), std::string::npos)
        << e.what();
  }
}

TEST(MeshReader, VineInstancedAlongARow) {
  const sim::TriangleMesh vine = read_mesh(kVine, sim::SurfaceClass::canopy);
  sim::TerrainConfig tc;
  tc.roughness = 0.0;
  sim::Field f;
  f.terrain = sim::Terrain(tc);
  // A row heading along +y (north) 51 m long: 10 instances of 5.1 m.
  sim::Row row;
  row.polyline = {{2.0, 0.0}, {2.0, 51.0}};
  f.rows.push_back(row);
  EXPECT_EQ(sim::instance_along_rows(f, vine, 5.1), 10);
  EXPECT_EQ(f.mesh.triangle_count(), 10u * 10082u);
  const auto b = f.mesh.bounds();
  EXPECT_NEAR(b.min().y(), -0.10, 0.02);
  EXPECT_NEAR(b.max().y(), 9 * 5.1 + 5.09, 0.02);
  // Instance x (across the row) maps to the right of the row, here world +x: -0.26..0.27 + 2.
  EXPECT_NEAR(b.min().x(), 2.0 - 0.26, 0.02);
  EXPECT_NEAR(b.max().x(), 2.0 + 0.27, 0.02);
  EXPECT_NEAR(b.max().z(), 1.58, 0.02);
}

}  // namespace
}  // namespace rownav::io
