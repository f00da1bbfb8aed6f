#include "rownav/io/layout_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>

#include "rownav/sim/field_config.hpp"
#include "rownav/sim/plant_geometry.hpp"

namespace rownav::io {
namespace {

const std::filesystem::path kJojos = std::filesystem::path(ROWNAV_SHARED_DATA) /
                                     "layouts/agrids_jojos_vineyard/jojos_vineyard.geojson";

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::path(::testing::TempDir()) / ("rownav_layout_" + name);
  std::ofstream(p) << text;
  return p;
}

/// Expects an InputError whose message contains `needle`.
template <class F>
void expect_input_error(F&& f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no InputError, expected '" << needle << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
}

TEST(GeoJsonLayout, RealJojosVineyard) {
  sim::RowLayout layout = read_geojson_layout(kJojos);
  // 93 LineStrings: 92 typed "row" plus one drainage line (type "line"), which is not a row.
  EXPECT_EQ(layout.rows.size(), 92u);
  std::set<int> blocks;
  for (const auto& r : layout.rows) blocks.insert(r.block);
  EXPECT_EQ(blocks.size(), 10u);
  // Origin at the first coordinate; the whole vineyard is ~200 m across.
  EXPECT_LT(layout.rows.front().polyline.front().norm(), 1e-6);
  for (const auto& r : layout.rows)
    for (const auto& p : r.polyline) ASSERT_LT(p.norm(), 400.0);
  sim::order_layout_rows(layout);
  for (int b : blocks) {
    sim::RowLayout one;
    for (const auto& r : layout.rows)
      if (r.block == b) one.rows.push_back(r);
    if (one.rows.size() < 2) continue;
    const double spacing = sim::estimate_row_spacing(one);
    EXPECT_GT(spacing, 2.2) << "block " << b;
    EXPECT_LT(spacing, 2.6) << "block " << b;
    // Sorted laterally: each row lies on the left of the previous one, about one spacing away.
    for (std::size_t k = 0; k + 1 < one.rows.size(); ++k) {
      const sim::PolylinePath a(one.rows[k].polyline);
      const Eigen::Vector2d mid = sim::PolylinePath(one.rows[k + 1].polyline).point(0.0);
      const double s = a.project(mid);
      const double lateral = a.left(s).dot(mid - a.point(s));
      EXPECT_GT(lateral, 0.5 * spacing) << "block " << b << " row " << k;
      EXPECT_LT(lateral, 1.5 * spacing) << "block " << b << " row " << k;
    }
  }
}

TEST(GeoJsonLayout, BlockFilterAndOrigin) {
  LayoutReadOptions opt;
  opt.blocks = {"2019-a-3"};
  const sim::RowLayout a = read_geojson_layout(kJojos, opt);
  EXPECT_EQ(a.rows.size(), 23u);
  for (const auto& r : a.rows) EXPECT_EQ(r.block, 0);
  // An origin 0.001 deg north of the first point puts it ~111 m south.
  opt.origin_lat_deg = 51.597218313361665 + 0.001;
  opt.origin_lon_deg = -0.9774786210983095;
  const sim::RowLayout b = read_geojson_layout(kJojos, opt);
  EXPECT_NEAR(b.rows.front().polyline.front().y(), -111.26, 0.2);
  EXPECT_NEAR(b.rows.front().polyline.front().x(), 0.0, 0.01);
  opt.blocks = {"no-such-block"};
  expect_input_error([&] { read_geojson_layout(kJojos, opt); }, "no-such-block");
}

TEST(GeoJsonLayout, PointsNamedAsPlantsJoinTheNearestRow) {
  const auto f = write_temp("plants.geojson", R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{"type":"row","block":"A"},"geometry":{"type":"LineString","coordinates":[[0,51],[0.001,51]]}},
    {"type":"Feature","properties":{"type":"row","block":"A"},"geometry":{"type":"LineString","coordinates":[[0,51.00003],[0.001,51.00003]]}},
    {"type":"Feature","properties":{"kind":"post"},"geometry":{"type":"Point","coordinates":[0.0005,51.000028]}},
    {"type":"Feature","properties":{"name":"gate"},"geometry":{"type":"Point","coordinates":[0.0005,51.00001]}}]})");
  const sim::RowLayout l = read_geojson_layout(f);
  ASSERT_EQ(l.rows.size(), 2u);
  ASSERT_EQ(l.plants.size(), 1u);
  EXPECT_EQ(l.plants[0].kind, sim::PlantKind::post);
  EXPECT_EQ(l.plants[0].row, 1);
  EXPECT_NEAR(l.rows[0].polyline.back().x(), 70.0, 0.5);  // 0.001 deg lon at 51 N
}

TEST(GeoJsonLayout, MalformedInputNamesThePosition) {
  expect_input_error([] { read_geojson_layout(write_temp("bad.geojson", "{\"type\": ")); }, "byte");
  expect_input_error(
      [] { read_geojson_layout(write_temp("notfc.geojson", "{\"type\":\"Feature\"}")); },
      "FeatureCollection");
  const std::string one_point = R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{},"geometry":{"type":"LineString","coordinates":[[0,51],[0.001,51]]}},
    {"type":"Feature","properties":{},"geometry":{"type":"LineString","coordinates":[[0,51]]}}]})";
  expect_input_error([&] { read_geojson_layout(write_temp("short.geojson", one_point)); },
                     ":feature 1:");
  const std::string bad_coord = R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{},"geometry":{"type":"LineString","coordinates":[[0,"x"],[0.001,51]]}}]})";
  expect_input_error([&] { read_geojson_layout(write_temp("coord.geojson", bad_coord)); },
                     ":feature 0:");
  expect_input_error(
      [] {
        read_geojson_layout(
            write_temp("empty.geojson", R"({"type":"FeatureCollection","features":[]})"));
      },
      "no rows");
  expect_input_error([] { read_geojson_layout("/nonexistent/layout.geojson"); }, "cannot open");
  expect_input_error([] { read_layout(write_temp("x.kml", "")); }, "unknown layout format");
}

TEST(CsvLayout, MetricRowsAndPlants) {
  const auto f = write_temp("ok.csv",
                            "# a two-row block\n"
                            "kind,block,row,x,y\n"
                            "row,A,r1,0,0\n"
                            "row,A,r1,10,0\n"
                            "\n"
                            "row,A,r2,0,2.5\n"
                            "row,A,r2,5,2.6\n"
                            "row,A,r2,10,2.5\n"
                            "end_post,A,r2,0,2.5\n"
                            "vine,A,r1,3,0\n");
  const sim::RowLayout l = read_csv_layout(f);
  ASSERT_EQ(l.rows.size(), 2u);
  EXPECT_EQ(l.rows[1].polyline.size(), 3u);
  EXPECT_DOUBLE_EQ(l.rows[1].polyline[1].y(), 2.6);
  ASSERT_EQ(l.plants.size(), 2u);
  EXPECT_EQ(l.plants[0].kind, sim::PlantKind::end_post);
  EXPECT_EQ(l.plants[0].row, 1);
  EXPECT_EQ(l.plants[1].row, 0);
  EXPECT_NEAR(sim::estimate_row_spacing(l), 2.6, 1e-9);
}

TEST(CsvLayout, LonLatBecomesLocalMetres) {
  const auto f = write_temp("geo.csv", "row,lon,lat\n1,0.0,51.0\n1,0.0,51.001\n");
  const sim::RowLayout l = read_csv_layout(f);
  EXPECT_NEAR(l.rows[0].polyline[1].y(), 111.25, 0.2);
  EXPECT_NEAR(l.rows[0].polyline[1].x(), 0.0, 1e-6);
}

TEST(CsvLayout, MalformedInputNamesTheLine) {
  expect_input_error([] { read_csv_layout(write_temp("c1.csv", "row,x,y\n1,0,0\n1,5\n")); },
                     ":line 3: expected 3 fields");
  expect_input_error([] { read_csv_layout(write_temp("c2.csv", "row,x,y\n1,0,0\n1,abc,0\n")); },
                     ":line 3: x: 'abc' is not a number");
  expect_input_error([] { read_csv_layout(write_temp("c3.csv", "row,x\n")); }, ":line 1: header");
  expect_input_error(
      [] {
        read_csv_layout(write_temp("c4.csv", "kind,row,x,y\nrow,1,0,0\nrow,1,1,0\nbush,1,0,0\n"));
      },
      ":line 4: kind: unknown 'bush'");
  expect_input_error(
      [] { read_csv_layout(write_temp("c5.csv", "row,x,y\n1,0,0\n2,0,1\n2,1,1\n")); },
      ":line 2: row '1' has fewer than 2 points");
  expect_input_error(
      [] {
        read_csv_layout(write_temp("c6.csv", "kind,row,x,y\nrow,1,0,0\nrow,1,1,0\npost,9,0,0\n"));
      },
      ":line 4: row '9' has no row points");
  expect_input_error([] { read_csv_layout(write_temp("c7.csv", "# nothing\n")); }, "no header");
  expect_input_error([] { read_csv_layout(write_temp("c8.csv", "row,x,y\n")); }, "no rows");
}

// Found by csv_layout_fuzz (issue 13): a '\r' inside a cell was copied into the message, which
// then was not one line on a terminal.
TEST(CsvLayout, ControlBytesOfACellAreEscapedInTheMessage) {
  const std::string cell = std::string("5H\r\x01", 4);
  for (const std::string& text : {"row,lon,lat\nr0,-0.1," + cell + "\n", "row,x,y," + cell + "\n",
                                  "kind,row,x,y\n" + cell + ",1,0,0\n"}) {
    try {
      read_csv_layout(write_temp("cr.csv", text));
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find_first_of("\r\n\x01"), std::string::npos) << what;
      EXPECT_NE(what.find("'5H\\r?'"), std::string::npos) << what;
    }
  }
}

// Found by geojson_layout_fuzz (issue 13): nlohmann::json throws out_of_range, not parse_error,
// for a number beyond a double; it escaped the reader without the file name.
TEST(GeoJsonLayout, NumberBeyondADoubleIsAnInputError) {
  expect_input_error(
      [] {
        read_geojson_layout(write_temp(
            "big.geojson",
            R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
            R"("geometry":{"type":"LineString","coordinates":[[0,51.59E719714182216],[0,51]]}}]})"));
      },
      "big.geojson: invalid JSON: a number is out of range");
}

}  // namespace
}  // namespace rownav::io
