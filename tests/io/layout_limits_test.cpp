// sim::LayoutLimits: a layout file with a mistyped coordinate, too many rows or deep JSON ends
// in one InputError naming the file, the position and the limit's key (issue 13).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "rownav/io/field_builder.hpp"
#include "rownav/io/layout_reader.hpp"

namespace rownav::io {
namespace {

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::path(::testing::TempDir()) / ("rownav_limits_" + name);
  std::ofstream(p) << text;
  return p;
}

std::string error_of(const std::filesystem::path& file, const LayoutReadOptions& opt = {}) {
  try {
    read_layout(file, opt);
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e.what();
  }
  ADD_FAILURE() << file << ": no InputError";
  return "";
}

/// Five 30 m rows 2.4 m apart; `extra` appended (more CSV lines).
std::string rows_csv(const std::string& extra = "") {
  std::ostringstream s;  // (not string +: GCC 12 warns falsely on it, -Wrestrict)
  s << "row,x,y,kind\n";
  for (int r = 0; r < 5; ++r)
    s << 'r' << r << ",0," << 2.4 * r << ",row\nr" << r << ",30," << 2.4 * r << ",row\n";
  s << extra;
  return s.str();
}

std::string geojson_row(double lat0, const std::string& props = R"({"type": "row"})") {
  return R"({"type": "Feature", "properties": )" + props +
         R"(, "geometry": {"type": "LineString", "coordinates": [[-0.1, )" + std::to_string(lat0) +
         R"(], [-0.1, 51.5003]]}})";
}

std::string collection(const std::string& features) {
  return R"({"type": "FeatureCollection", "features": [)" + features + "]}";
}

TEST(LayoutLimits, AValidLayoutIsWithinEveryLimit) {
  EXPECT_EQ(read_layout(write_temp("ok.csv", rows_csv("r4,15,9.6,post\n"))).rows.size(), 5u);
  EXPECT_EQ(read_layout(write_temp("ok.geojson", collection(geojson_row(51.5)))).rows.size(), 1u);
}

TEST(LayoutLimits, OneFarOffPointIsNamed) {
  // A post at x = 2^32 (CSV line 12) and a row starting at latitude 0 instead of 51.5.
  const std::string csv = error_of(write_temp("far.csv", rows_csv("r4,4294967296,9.6,post\n")));
  EXPECT_NE(csv.find("far.csv:line 12: layout.limits.max_extent"), std::string::npos) << csv;
  const std::string gj =
      error_of(write_temp("far.geojson", collection(geojson_row(51.5) + "," + geojson_row(0.0) +
                                                    "," + geojson_row(51.5))));
  EXPECT_NE(gj.find("far.geojson:feature 1: layout.limits.max_extent"), std::string::npos) << gj;
}

TEST(LayoutLimits, CountsAndLengthAreBounded) {
  LayoutReadOptions opt;
  opt.limits.max_rows = 4;
  EXPECT_NE(
      error_of(write_temp("rows.csv", rows_csv()), opt).find(":line 10: layout.limits.max_rows"),
      std::string::npos);
  opt = {};
  opt.limits.max_plants = 1;
  EXPECT_NE(error_of(write_temp("plants.csv", rows_csv("r0,1,0,post\nr0,2,0,post\n")), opt)
                .find(":line 13: layout.limits.max_plants"),
            std::string::npos);
  opt = {};
  opt.limits.max_total_row_length = 100.0;  // 5 x 30 m
  EXPECT_NE(error_of(write_temp("len.csv", rows_csv()), opt)
                .find("layout.limits.max_total_row_length: the rows add up to 150 m"),
            std::string::npos);
}

TEST(LayoutLimits, DeepJsonIsRefusedWithoutRecursion) {
  // 100,000 nested arrays in a property: parsed to depth 64 only, never dumped.
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const std::string e = error_of(write_temp(
      "deep.geojson", collection(geojson_row(51.5, R"({"type": "row", "block": )" + deep + "}"))));
  EXPECT_NE(e.find("deep.geojson:byte "), std::string::npos) << e;
  EXPECT_NE(e.find("layout.limits.max_json_depth"), std::string::npos) << e;
  // Shallow but structured names are refused, not dumped into the block name.
  const std::string shallow = error_of(write_temp(
      "obj.geojson", collection(geojson_row(51.5, R"({"type": "row", "block": [1, [2]]})"))));
  EXPECT_NE(shallow.find(":feature 0: properties.block: expected a string or a number"),
            std::string::npos)
      << shallow;
}

TEST(LayoutLimits, RowSpacingIsBoundedBeforeDressing) {
  sim::FieldConfig c;
  c.kind = sim::FieldKind::layout;
  c.layout.file = write_temp("wide.csv", "row,x,y\na,0,0\na,30,0\nb,0,500\nb,30,500\n").string();
  try {
    build_field(c, ".");
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wide.csv: layout.limits.max_row_spacing"),
              std::string::npos)
        << e.what();
  }
  c.layout.limits.max_extent = 0.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::io
