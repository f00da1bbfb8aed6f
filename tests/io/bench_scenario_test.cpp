// Benchmark scenario files and their expansion into cells.
#include "rownav/io/bench_scenario.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include <fstream>
#include <set>

#include "common/bench_fake.hpp"
#include "common/cli_runner.hpp"
#include "rownav/io/bench_matrix.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/sim/field_config.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

std::string load_error(const fs::path& file) {
  try {
    load_scenario(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(BenchScenario, GoodFileLoadsWithSeedList) {
  TempDir dir("bench");
  const auto file = test::write_test_scenario(dir.path(), "[pearl, ruby]", "[4, 5, 6]");
  const BenchScenario s = load_scenario(file);
  ASSERT_EQ(s.matrices.size(), 1u);
  EXPECT_EQ(s.name, "test");
  EXPECT_EQ(s.matrices[0].detectors, (std::vector<std::string>{"pearl", "ruby"}));
  EXPECT_EQ(s.matrices[0].seed_list(), (std::vector<std::uint64_t>{4, 5, 6}));
  EXPECT_EQ(s.matrices[0].tables.size(), 3u);
  EXPECT_EQ(s.base_dir, dir.path().lexically_normal());
}

TEST(BenchScenario, UnknownKeyIsOneLineErrorWithPosition) {
  TempDir dir("bench");
  const auto file = test::write_test_scenario(dir.path(), "[pearl]", "[1]", "    speed: 2\n");
  const std::string e = load_error(file);
  EXPECT_NE(e.find(file.string() + ":14:5: unknown key 'speed'"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos);
}

TEST(BenchScenario, BadTypeAndBadTableAreErrorsAtTheValue) {
  TempDir dir("bench");
  auto file = test::write_test_scenario(dir.path(), "[pearl]", "[1]", "    time_limit: soon\n");
  std::string e = load_error(file);
  EXPECT_NE(e.find(":14:17: matrices[0].time_limit: expected a number"), std::string::npos) << e;
  file = test::write_test_scenario(dir.path(), "[pearl]", "oops");
  e = load_error(file);
  EXPECT_NE(e.find(":12:12: matrices[0].seeds: expected a list"), std::string::npos) << e;
}

TEST(BenchScenario, MissingFileAndEmptyListAreErrors) {
  TempDir dir("bench");
  auto file = test::write_test_scenario(dir.path(), "[pearl]", "[1]");
  fs::remove(dir / "robot.yaml");
  EXPECT_NE(load_error(file).find(":6:14: matrices[0].robots[0]: no such file"), std::string::npos)
      << load_error(file);
  EXPECT_NO_THROW(load_scenario(file, false));
  file = test::write_test_scenario(dir.path(), "[]", "[1]");
  EXPECT_NE(load_error(file).find("matrices[0].detectors: must not be empty"), std::string::npos);
}

TEST(BenchMatrix, CountsAndStableUniqueIds) {
  TempDir dir("bench");
  const auto file = test::write_test_scenario(
      dir.path(), "[pearl, ruby]", "[1, 2, 3]",
      "    row_end_policies: [nearest, line_fitting]\n"
      "  - name: again\n    fields: [f1.yaml]\n    robots: [robot.yaml]\n"
      "    sensors: [sensor.yaml]\n    missions: [mission.yaml]\n    detectors: [pearl]\n"
      "    trackers: [model_filter, none]\n    controllers: [lookahead_pid]\n"
      "    row_end_policies: [nearest]\n    seed_count: 1\n    tables: [lan_001]\n");
  const auto cells = expand_scenario(load_scenario(file));
  // 2 detectors x 2 policies x 3 seeds = 12; the second matrix adds only its `none` cell.
  ASSERT_EQ(cells.size(), 13u);
  std::set<std::string> ids;
  for (const auto& c : cells) ids.insert(c.id);
  EXPECT_EQ(ids.size(), cells.size());
  EXPECT_EQ(cells[0].id.rfind("f1_pearl_model_filter_lookahead_pid_nearest_s1-", 0), 0u)
      << cells[0].id;
  EXPECT_EQ(cells[0].matrices, (std::vector<std::string>{"m", "again"}));
  EXPECT_TRUE(cells[0].feeds(BenchTable::lan_001));
  EXPECT_TRUE(cells[0].feeds(BenchTable::timing));
  EXPECT_FALSE(cells[1].feeds(BenchTable::lan_001));
  const auto again = expand_scenario(load_scenario(file));
  for (std::size_t i = 0; i < cells.size(); ++i) EXPECT_EQ(again[i].id, cells[i].id);
}

TEST(BenchMatrix, RunArgsCarryEverySetting) {
  TempDir dir("bench");
  const auto cells = expand_scenario(load_scenario(
      test::write_test_scenario(dir.path(), "[pearl]", "[7]", "    time_limit: 90\n")));
  ASSERT_EQ(cells.size(), 1u);
  const auto a = cells[0].run_args("OUT/x");
  const auto after = [&](const std::string& k) {
    const auto it = std::find(a.begin(), a.end(), k);
    return it == a.end() || it + 1 == a.end() ? std::string("?") : *(it + 1);
  };
  EXPECT_EQ(after("--seed"), "7");
  EXPECT_EQ(after("--time-limit"), "90");
  EXPECT_EQ(after("--out"), "OUT/x");
  EXPECT_EQ(after("--field"), (dir.path() / "f1.yaml").lexically_normal().string());
}

// A matrix over the seeded zoo: fields by reference, bands filtered, the crop's detector.
fs::path write_zoo_scenario(const fs::path& dir, const std::string& bands) {
  for (const char* f : {"robot.yaml", "sensor.yaml", "mission.yaml"}) std::ofstream(dir / f) << "{}\n";
  const auto file = dir / "zoo.yaml";
  std::ofstream(file) << "name: zoo\nroot: .\nmatrices:\n  - name: z\n    zoo_count: 10\n"
                         "    zoo_first: 5\n    zoo_seed: 3\n    zoo_bands: " << bands << "\n"
                         "    robots: [robot.yaml]\n    sensors: [sensor.yaml]\n"
                         "    missions: [mission.yaml]\n    detectors: [default]\n"
                         "    trackers: [model_filter]\n    controllers: [stanley]\n"
                         "    seeds: [1]\n    tables: [fields]\n";
  return file;
}

TEST(BenchMatrix, ZooFieldsExpandByReferenceWithTheCropDetector) {
  TempDir dir("bench");
  const auto cells = expand_scenario(load_scenario(write_zoo_scenario(dir.path(), "[row_crop, orchard_free]")));
  // Indices 5..14: band i % 5; row_crop is band 4 (9, 14), orchard_free band 2 (7, 12).
  ASSERT_EQ(cells.size(), 4u);
  std::set<std::string> refs;
  for (const auto& c : cells) refs.insert(c.field.string());
  EXPECT_EQ(refs, (std::set<std::string>{"zoo:3:7", "zoo:3:9", "zoo:3:12", "zoo:3:14"}));
  EXPECT_EQ(cells[0].field_name(), "zoo_3_7_orchard_free");
  EXPECT_EQ(cells[0].id.rfind("zoo_3_7_orchard_free_default_", 0), 0u) << cells[0].id;
  const auto a = cells[0].run_args("OUT/x");
  EXPECT_EQ(std::find(a.begin(), a.end(), "--detector"), a.end());  // the crop's detector
  const auto field = std::find(a.begin(), a.end(), "--field");
  ASSERT_NE(field, a.end());
  EXPECT_EQ(*(field + 1), "zoo:3:7");
  EXPECT_NE(load_error(write_zoo_scenario(dir.path(), "[vineyard]"))
                .find("matrices[0].zoo_bands[0]: not a zoo band"),
            std::string::npos);
  EXPECT_EQ(load_error(write_zoo_scenario(dir.path(), "[]")), "");  // no filter: every band
  EXPECT_EQ(expand_scenario(load_scenario(write_zoo_scenario(dir.path(), "[]"))).size(), 10u);
}

TEST(BenchScenario, RepositoryScenariosAndFieldsLoad) {
  const fs::path src(ROWNAV_SOURCE_DIR);
  const auto quick = expand_scenario(load_scenario(src / "bench/scenarios/quick.yaml", false));
  EXPECT_EQ(quick.size(), 4u);  // as stated in quick.yaml
  const auto full = expand_scenario(load_scenario(src / "bench/scenarios/full.yaml", false));
  EXPECT_EQ(full.size(), 536u);  // as stated in full.yaml
  const auto malavazi =
      expand_scenario(load_scenario(src / "bench/scenarios/malavazi.yaml", false));
  ASSERT_EQ(malavazi.size(), 240u);  // 4 detectors x 2 variants x 3 levels x 10 seeds
  const auto zoo = expand_scenario(load_scenario(src / "bench/scenarios/zoo.yaml", false));
  EXPECT_EQ(zoo.size(), 100u + 17u);  // as stated in zoo.yaml
  const auto& args = malavazi.front().extra_args;  // config files resolved against the root
  const auto nav = std::find(args.begin(), args.end(), "--nav-config");
  ASSERT_NE(nav, args.end());
  ASSERT_NE(nav + 1, args.end());
  EXPECT_TRUE(fs::exists(*(nav + 1))) << *(nav + 1);
  for (const auto& e : fs::directory_iterator(src / "bench/fields"))
    EXPECT_NO_THROW(load_config<sim::FieldConfig>(e.path())) << e.path();
}

}  // namespace
}  // namespace rownav::io
