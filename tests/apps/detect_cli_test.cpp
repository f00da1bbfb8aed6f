// End-to-end tests of `rownav detect`: the real binary (ROWNAV_BINARY) on small inputs written
// by the tests, in a fresh temporary directory.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "common/cli_runner.hpp"
#include "common/synthetic_rows.hpp"
#include "rownav/io/cloud_io.hpp"

namespace rownav {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::Result;
using test::rownav;
using test::TempDir;

std::vector<std::string> lines_of(const fs::path& file) {
  std::vector<std::string> out;
  std::ifstream in(file);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// The number after "key": in a JSON line (first occurrence after `from`).
double number_after(const std::string& line, const std::string& key, std::size_t from = 0) {
  const auto p = line.find("\"" + key + "\":", from);
  if (p == std::string::npos) return std::nan("");
  return std::stod(line.substr(p + key.size() + 3));
}

// Two maize rows at y = +-0.375, straight ahead (base frame).
test::SyntheticScene maize() {
  test::SyntheticRows s;
  s.rows = 2;
  s.spacing = 0.75;
  s.x_max = 3.0;
  s.canopy_half_width = 0.03;
  return test::make_rows(s);
}

TEST(DetectCli, FramedPointsCsvGivesOneLinePerFrame) {
  TempDir dir;
  std::ofstream csv(dir / "scans.csv");
  csv << "frame,x,y\n";
  const auto scene = maize();
  for (const int frame : {7, 9})
    for (const auto& p : scene.points) csv << frame << "," << p.x() << "," << p.y() << "\n";
  csv.close();
  const Result r = rownav(
      dir.path(), "detect --detector baseline --in scans.csv --out rows.json --svg view.svg");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = lines_of(dir / "rows.json");
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].rfind("{\"frame\":7,\"stamp\":7", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1].rfind("{\"frame\":9,", 0), 0u) << lines[1];
  EXPECT_NE(lines[0].find("\"status\":\"ok\""), std::string::npos);
  const auto left = lines[0].find("\"left\":"), right = lines[0].find("\"right\":");
  EXPECT_NEAR(number_after(lines[0], "offset", left), 0.375, 0.02);
  EXPECT_NEAR(number_after(lines[0], "offset", right), -0.375, 0.02);
  EXPECT_NEAR(number_after(lines[0], "width", lines[0].find("\"corridor\":")), 0.75, 0.03);
  EXPECT_NE(read_file(dir / "view.svg").find("<svg"), std::string::npos);
}

TEST(DetectCli, PcdCloudWithMount) {
  TempDir dir;
  // LiDAR 0.5 m up, turned 90 deg left: base (x, y) is LiDAR (y, -x); plants 0.3-0.6 m tall.
  core::PointCloud cloud;
  cloud.stamp = 12.5;
  for (const auto& p : maize().points)
    for (const float z : {0.3f, 0.6f}) cloud.points.push_back({p.y(), -p.x(), z - 0.5f});
  io::write_cloud_pcd(dir / "frame.pcd", cloud);
  const Result r =
      rownav(dir.path(), "detect --detector baseline --config '" + std::string(ROWNAV_SOURCE_DIR) +
                             "/config/detect/row_crop.yaml' --in frame.pcd --out rows.json "
                             "--lidar-mount 0,0,0.5,0,0,90");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = lines_of(dir / "rows.json");
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].rfind("{\"stamp\":12.5,\"status\":\"ok\"", 0), 0u) << lines[0];
  EXPECT_NEAR(number_after(lines[0], "heading_deg"), 0.0, 1.0);
  EXPECT_NEAR(number_after(lines[0], "offset", lines[0].find("\"left\":")), 0.375, 0.02);
}

TEST(DetectCli, MalformedInputIsOneErrorLine) {
  TempDir dir;
  std::ofstream(dir / "bad.csv") << "x,y\n1.0,0.3\n1.5,oops\n";
  std::ofstream(dir / "bad.pcd") << "not a pcd\n";
  std::ofstream(dir / "ok.csv") << "1.0,0.3\n1.5,0.3\n";
  std::ofstream(dir / "bad.yaml") << "baseline:\n  y_max: -1\n";
  for (const std::string args :
       {"--detector baseline --in bad.csv --out o.json",
        "--detector baseline --in bad.pcd --out o.json", "--detector nope --in ok.csv --out o.json",
        "--detector baseline --config bad.yaml --in ok.csv --out o.json",
        "--detector baseline --in ok.csv --out o.json --lidar-mount 1,2",
        "--detector baseline --in missing.csv --out o.json"}) {
    const Result r = rownav(dir.path(), "detect " + args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_TRUE(std::regex_match(r.err, std::regex("rownav: error: [^\n]+\n")))
        << args << ": " << r.err;
    // No half-written output: neither the file nor its partial twin is left behind.
    EXPECT_FALSE(fs::exists(dir / "o.json")) << args;
    EXPECT_FALSE(fs::exists(dir / "o.json.partial")) << args;
  }
  const Result r = rownav(dir.path(), "detect --detector nope --in ok.csv --out o.json");
  EXPECT_NE(r.err.find("baseline"), std::string::npos) << r.err;
}

TEST(DetectCli, HelpStatesUnitsAndFrames) {
  TempDir dir;
  const Result r = rownav(dir.path(), "detect --help");
  ASSERT_EQ(r.code, 0);
  for (const char* s : {"x forward, y left", "metres", "degrees", "--lidar-mount", "baseline"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s;
}

TEST(DetectCli, RecordingUsesItsMount) {
  TempDir dir;
  std::ofstream(dir / "field.yaml") << "kind: row_crop\nname: tiny\nseed: 3\nrow_crop:\n  rows: 4\n"
                                       "  row_length: 6.0\n";
  const Result sim =
      rownav(dir.path(), "sim --field field.yaml --lidar lms_1081 --out rec --quiet");
  ASSERT_EQ(sim.code, 0) << sim.err;
  const Result r = rownav(
      dir.path(), "detect --detector baseline --in rec --out rows.json --svg v.png --svg-frame 1");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = lines_of(dir / "rows.json");
  ASSERT_GT(lines.size(), 2u);
  EXPECT_EQ(lines[1].rfind("{\"frame\":1,", 0), 0u) << lines[1];
  EXPECT_TRUE(fs::exists(dir / "v.png"));
}

}  // namespace
}  // namespace rownav
