// End-to-end tests of the `rownav` command line: the real binary (ROWNAV_BINARY) run through
// the shell in a fresh temporary directory, its exit code, stdout and stderr captured.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "common/cli_runner.hpp"
#include "rownav/io/recording.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/robot.hpp"
#include "rownav/sim/scripted_path.hpp"
#include "rownav/sim/simulator.hpp"

namespace rownav {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::Result;
using test::rownav;
using test::TempDir;

void write_file(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << text;
}

/// 4 rows x 15 m, 2 m apart: a drive through the default corridors 0 and 1 takes ~50 s
/// simulated, a fraction of a second with a 2D LiDAR.
const char* const kTinyField =
    "# tiny test field\n"
    "kind: vineyard\n"
    "name: tiny\n"
    "seed: 4\n"
    "vineyard:\n"
    "  rows: 4\n"
    "  row_length: 15.0\n"
    "  row_spacing: 2.0\n"
    "terrain:\n"
    "  roughness: 0.01\n";

bool has_png_signature(const fs::path& file) {
  return read_file(file).rfind("\x89PNG\r\n\x1a\n", 0) == 0;
}

/// One recording made by `rownav sim` for the whole suite (render reads it too).
class Cli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir("suite");
    write_file(*dir_ / "field.yaml", kTinyField);
    sim_ = new Result(
        rownav(dir_->path(), "sim --field field.yaml --lidar lms_1081 --out rec --quiet"));
  }
  static void TearDownTestSuite() {
    delete sim_;
    delete dir_;
    sim_ = nullptr;
    dir_ = nullptr;
  }
  static TempDir* dir_;
  static Result* sim_;
};
TempDir* Cli::dir_ = nullptr;
Result* Cli::sim_ = nullptr;

template <class T, class Stamp>
void expect_increasing(const std::vector<T>& v, Stamp stamp, const char* what) {
  for (std::size_t i = 1; i < v.size(); ++i)
    ASSERT_GT(stamp(v[i]), stamp(v[i - 1])) << what << " " << i;
}

TEST_F(Cli, SimWritesACompleteRecording) {
  ASSERT_EQ(sim_->code, 0) << sim_->err;
  EXPECT_EQ(sim_->err, "");  // --quiet: no progress bar
  EXPECT_NE(sim_->out.find("path completed"), std::string::npos) << sim_->out;
  const fs::path rec = *dir_ / "rec";
  for (const char* f : {"manifest.yaml", "lidar/scans.csv", "ground_truth.csv", "encoders.csv",
                        "imu.csv", "field/rows.csv", "top_view.png"})
    EXPECT_TRUE(fs::is_regular_file(rec / f)) << f;
  EXPECT_FALSE(fs::exists(*dir_ / "rec.partial"));
  EXPECT_TRUE(has_png_signature(rec / "top_view.png"));

  const io::Recording r = io::read_recording(rec);
  EXPECT_EQ(r.manifest["field"]["name"].as<std::string>(), "tiny");
  EXPECT_EQ(r.rows.size(), 4u);
  EXPECT_EQ(r.cloud_count(), 0u);  // a 2D LiDAR: scans only
  ASSERT_FALSE(r.imu.empty());
  // Duration: the IMU runs at the physics rate (100 Hz), so its last stamp is the sim time.
  const double T = r.imu.back().stamp;
  RecordProperty("sim_time", std::to_string(T));
  EXPECT_GT(T, 40.0);  // lead-in 2 m, 2 x 15 m lanes, a U-turn, lead-out at <= 1 m/s
  EXPECT_LT(T, 70.0);
  // Every stream at its rate (lms_1081 25 Hz, encoders 50 Hz, IMU 100 Hz, truth 20 Hz).
  EXPECT_NEAR(static_cast<double>(r.scans.size()), 25.0 * T, 2.0);
  EXPECT_NEAR(static_cast<double>(r.encoders.size()), 50.0 * T, 2.0);
  EXPECT_NEAR(static_cast<double>(r.imu.size()), 100.0 * T, 2.0);
  EXPECT_NEAR(static_cast<double>(r.ground_truth.size()), 20.0 * T, 2.0);
  EXPECT_TRUE(r.gnss.empty());  // disabled by default
  expect_increasing(
      r.scans, [](const auto& s) { return s.stamp; }, "scans");
  expect_increasing(
      r.encoders, [](const auto& s) { return s.stamp; }, "encoders");
  expect_increasing(
      r.imu, [](const auto& s) { return s.stamp; }, "imu");
  expect_increasing(
      r.ground_truth, [](const auto& s) { return s.stamp; }, "truth");
  ASSERT_FALSE(r.scans.empty());
  EXPECT_EQ(r.scans.front().ranges.size(), 1081u);
  // The drive went through corridors 0 and 1 without touching a vine.
  bool lane0 = false, lane1 = false;
  for (const auto& g : r.ground_truth) {
    lane0 |= g.place == sim::Place::lane && g.corridor == 0;
    lane1 |= g.place == sim::Place::lane && g.corridor == 1;
    if (g.place == sim::Place::lane) {
      EXPECT_LT(std::abs(g.lateral_error), 0.2) << g.stamp;
    }
  }
  EXPECT_TRUE(lane0);
  EXPECT_TRUE(lane1);
  EXPECT_EQ(r.ground_truth.back().plants_crushed, 0);
}

/// A bad input: the files to write (relative path, content) and what the error must say.
struct BadCase {
  std::string name;
  std::vector<std::pair<std::string, std::string>> files;
  std::string args;   ///< after `rownav sim --out out --quiet --lidar lms_1081`
  std::string where;  ///< regex the message must match right after "rownav: error: "
};

std::vector<BadCase> bad_cases() {
  const std::string csv_ok = "row,x,y\n1,0,0\n1,15,0\n2,0,2\n2,15,2\n3,0,4\n3,15,4\n";
  const std::string layout_with_mesh = "kind: layout\nlayout:\n  file: rows.csv\n  instance_mesh: ";
  std::string stl0(80, '\0');  // binary STL: 80-byte header, then a 0 triangle count
  stl0.append(4, '\0');
  return {
      {"malformed_yaml",
       {{"field.yaml", "kind: vineyard\nvineyard:\n  rows: 4\n   row_length: 15\n"}},
       "--field field.yaml",
       R"(field\.yaml:4:\d+: invalid YAML)"},
      {"unknown_key",
       {{"field.yaml", "kind: vineyard\nvineyard:\n  rows: 4\n  row_lenght: 15\n"}},
       "--field field.yaml",
       R"(field\.yaml:4:3: unknown key 'row_lenght' in 'vineyard' \(valid: rows, )"},
      {"wrong_type",
       {{"field.yaml", "kind: vineyard\nvineyard:\n  rows: 4\n  row_spacing: abc\n"}},
       "--field field.yaml",
       R"(field\.yaml:4:16: vineyard\.row_spacing: expected a number, got 'abc')"},
      {"zero_rows",
       {{"field.yaml", "kind: vineyard\nvineyard:\n  rows: 0\n"}},
       "--field field.yaml",
       R"(field\.yaml:3:3: vineyard\.rows: must be in \[1, 1000\] \(got 0\))"},
      {"csv_bad_number",
       {{"field.yaml", "kind: layout\nlayout:\n  file: rows.csv\n"},
        {"rows.csv", "row,x,y\n1,0,0\n1,15,0\n2,0,2\n2,15,2.x\n"}},
       "--field field.yaml",
       R"(rows\.csv:line 5: y: '2\.x' is not a number)"},
      {"geojson_truncated",
       {{"field.yaml", "kind: layout\nlayout:\n  file: rows.geojson\n"},
        {"rows.geojson", "{\"type\": \"FeatureCollection\", \"features\": [{\"type\": "}},
       "--field field.yaml",
       R"(rows\.geojson:byte \d+: invalid JSON)"},
      {"geojson_bad_coordinates",
       {{"field.yaml", "kind: layout\nlayout:\n  file: rows.geojson\n"},
        {"rows.geojson",
         "{\"type\": \"FeatureCollection\", \"features\": [{\"type\": \"Feature\", "
         "\"properties\": {}, \"geometry\": {\"type\": \"LineString\", \"coordinates\": "
         "[[-0.97, 51.59], \"north\"]}}]}"}},
       "--field field.yaml",
       R"(rows\.geojson:feature 0: .+)"},
      {"empty_obj",
       {{"field.yaml", layout_with_mesh + "vine.obj\n"}, {"rows.csv", csv_ok}, {"vine.obj", ""}},
       "--field field.yaml",
       R"(field\.yaml:4:18: layout\.instance_mesh: vine\.obj: .+)"},
      {"obj_without_faces",
       {{"field.yaml", layout_with_mesh + "vine.obj\n"},
        {"rows.csv", csv_ok},
        {"vine.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"}},
       "--field field.yaml",
       R"(field\.yaml:4:18: layout\.instance_mesh: vine\.obj: .+)"},
      {"stl_zero_triangles",
       {{"field.yaml", layout_with_mesh + "vine.stl\n"}, {"rows.csv", csv_ok}, {"vine.stl", stl0}},
       "--field field.yaml",
       R"(field\.yaml:4:18: layout\.instance_mesh: vine\.stl: .+)"},
      {"path_leaves_field",
       {{"field.yaml", kTinyField}, {"path.yaml", "speed: 1.0\ncorridors: [1, 99]\n"}},
       "--field field.yaml --path path.yaml",
       R"(path\.yaml:2:16: corridors\[1\]: corridor 99 does not exist in block 0 \(0\.\.2\))"},
      {"missing_layout_file",
       {{"field.yaml", "kind: layout\nlayout:\n  file: nowhere.csv\n"}},
       "--field field.yaml",
       R"(field\.yaml:3:9: layout\.file: nowhere\.csv: .+)"},
      {"missing_field_file", {}, "--field nowhere.yaml", R"(--field: .*nowhere\.yaml.*)"},
  };
}

TEST(CliErrors, BadInputGivesOneLineAndNoOutput) {
  for (const BadCase& c : bad_cases()) {
    SCOPED_TRACE(c.name);
    TempDir dir(c.name);
    for (const auto& [rel, text] : c.files) write_file(dir / rel, text);
    const Result r = rownav(dir.path(), "sim --out out --quiet --lidar lms_1081 " + c.args);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    ASSERT_FALSE(r.err.empty());
    EXPECT_EQ(r.err.back(), '\n');
    const std::string line = r.err.substr(0, r.err.find('\n'));
    EXPECT_TRUE(std::regex_search(line, std::regex("^rownav: error: " + c.where)))
        << line << "\n  expected after the prefix: " << c.where;
    EXPECT_FALSE(fs::exists(dir / "out"));
    EXPECT_FALSE(fs::exists(dir / "out.partial"));
  }
}

TEST_F(Cli, RenderWritesPngSvgAndPdfLiveAndFromTheRecording) {
  ASSERT_EQ(sim_->code, 0) << sim_->err;
  for (const char* ext : {"png", "svg", "pdf"}) {
    SCOPED_TRACE(ext);
    const std::string live = std::string("live.") + ext, recorded = std::string("recorded.") + ext;
    const Result a = rownav(dir_->path(), "render --field field.yaml --corridor 1 --out " + live);
    EXPECT_EQ(a.code, 0) << a.err;
    EXPECT_EQ(a.err, "");
    const Result b =
        rownav(dir_->path(), "render --field field.yaml --recording rec --out " + recorded);
    EXPECT_EQ(b.code, 0) << b.err;
    for (const std::string& f : {live, recorded}) {
      ASSERT_TRUE(fs::is_regular_file(*dir_ / f)) << f;
      EXPECT_GT(fs::file_size(*dir_ / f), 1000u) << f;
      if (std::string(ext) == "png") {
        EXPECT_TRUE(has_png_signature(*dir_ / f)) << f;
      } else if (std::string(ext) == "pdf") {
        EXPECT_EQ(read_file(*dir_ / f).rfind("%PDF-", 0), 0u) << f;
      } else {
        const std::string svg = read_file(*dir_ / f);
        EXPECT_NE(svg.find("<svg"), std::string::npos) << f;
        EXPECT_NE(svg.find("</svg>"), std::string::npos) << f;  // complete
      }
    }
  }
  // A corridor the field does not have: one error line, no picture.
  const Result bad = rownav(dir_->path(), "render --field field.yaml --corridor 7 --out bad.png");
  EXPECT_EQ(bad.code, 2);
  EXPECT_EQ(bad.err, "rownav: error: --corridor 7 does not exist\n");
  EXPECT_FALSE(fs::exists(*dir_ / "bad.png"));
  // A pose off the field or not a number: one error line naming --pose, no picture (issue 13).
  for (const std::string pose : {"1e30,0,0", "nan,0,0", "0,inf,0", "2,0,1e300", "-500,0,0"}) {
    const Result off = rownav(dir_->path(), "render --field field.yaml --pose " + pose +
                                                " --out off.png");
    EXPECT_EQ(off.code, 2) << pose;
    EXPECT_EQ(off.err.rfind("rownav: error: --pose", 0), 0u) << pose << ": " << off.err;
    EXPECT_EQ(std::count(off.err.begin(), off.err.end(), '\n'), 1) << off.err;
    EXPECT_FALSE(fs::exists(*dir_ / "off.png")) << pose;
  }
  // An unknown picture format names the user's file (not the staging one), before the work.
  const Result bmp = rownav(dir_->path(), "render --field field.yaml --corridor 1 --out v.bmp");
  EXPECT_EQ(bmp.code, 2);
  EXPECT_EQ(bmp.err.rfind("rownav: error: v.bmp: unknown picture format '.bmp'", 0), 0u) << bmp.err;
  EXPECT_FALSE(fs::exists(*dir_ / "v.bmp"));
}

TEST(CliZoo, AZooReferenceIsAFieldAndABadOneIsAOneLineError) {
  TempDir dir("zoo");
  // Field 4 of zoo 1 is a row crop: `render` builds it from the reference alone.
  Result r = rownav(dir.path(), "render --field zoo:1:4 --out zoo.png");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(has_png_signature(dir / "zoo.png"));
  r = rownav(dir.path(), "zoo --first 4 --count 1");
  EXPECT_NE(r.out.find("zoo_1_4_row_crop"), std::string::npos) << r.out;
  r = rownav(dir.path(), "render --field zoo:1:x --out bad.png");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("zoo:SEED:INDEX"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir / "bad.png"));
}

TEST(CliConfig, DumpedDefaultsAreAcceptedBack) {
  TempDir dir("config");
  for (const char* what : {"field", "robot", "sensors", "path"}) {
    const Result r = rownav(dir.path(), std::string("config --dump ") + what);
    ASSERT_EQ(r.code, 0) << what << ": " << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(r.out.find(':'), std::string::npos) << what;
    write_file(dir / (std::string(what) + ".yaml"), r.out);
  }
  // The dump decodes strictly to the defaults: encoding them again gives the same YAML.
  auto emit = [](const YAML::Node& n) {
    YAML::Emitter e;
    e << n;
    return std::string(e.c_str());
  };
  const auto field = io::load_config<sim::FieldConfig>(dir / "field.yaml");
  EXPECT_EQ(emit(io::encode_config(field)), emit(io::encode_config(sim::FieldConfig{})));
  const auto robot = io::load_config<sim::RobotConfig>(dir / "robot.yaml");
  EXPECT_EQ(emit(io::encode_config(robot)), emit(io::encode_config(sim::RobotConfig{})));
  const auto path = io::load_config<sim::PathConfig>(dir / "path.yaml");
  EXPECT_EQ(emit(io::encode_config(path)), emit(io::encode_config(sim::PathConfig{})));
  // And `rownav sim` accepts every dumped file (default 10 x 50 m vineyard, OS1-16 at 10 Hz;
  // 2 s simulated keep it short).
  const Result sim = rownav(dir.path(),
                            "sim --field field.yaml --robot robot.yaml --sensors sensors.yaml "
                            "--path path.yaml --max-time 2 --out rec --quiet");
  ASSERT_EQ(sim.code, 0) << sim.err;
  const io::Recording rec = io::read_recording(dir / "rec");
  EXPECT_NEAR(static_cast<double>(rec.cloud_count()), 20.0, 1.0);
  EXPECT_EQ(rec.rows.size(), 10u);
}

}  // namespace
}  // namespace rownav
