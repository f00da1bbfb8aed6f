// End-to-end tests of `rownav bench` with a fake runner (tests/common/bench_fake.hpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/bench_fake.hpp"
#include "common/cli_runner.hpp"

namespace rownav {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::Result;
using test::rownav;
using test::TempDir;

TEST(BenchCli, RunsResumesAndWritesTables) {
  TempDir dir("bench_cli");
  test::write_test_scenario(dir.path(), "[pearl]", "[1, 2]");
  const std::string runner = test::write_fake_runner(dir.path()).string();
  const std::string args = "bench --scenario scenario.yaml --out out -j 2 --runner " + runner;
  Result r = rownav(dir.path(), args);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("ran 2, resumed 0, failed 0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("tables: out/tables.md, out/tables.json"), std::string::npos) << r.out;
  EXPECT_NE(read_file(dir / "out/tables.md").find("| pearl | filtered (model_filter) | 2 | 100 |"),
            std::string::npos)
      << read_file(dir / "out/tables.md");
  r = rownav(dir.path(), args);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("ran 0, resumed 2"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("resumed: summary.json exists"), std::string::npos) << r.err;
}

TEST(BenchCli, BaselineGateAndUpdate) {
  TempDir dir("bench_cli");
  test::write_test_scenario(dir.path(), "[pearl]", "[1, 3]");
  const std::string args = "bench --scenario scenario.yaml --out out --runner " +
                           test::write_fake_runner(dir.path()).string() + " --baseline b.json";
  std::ofstream(dir / "b.json")
      << R"({"metrics": {"success_rate": {"value": 40, "better": "higher", "tolerance": 0}}})";
  Result r = rownav(dir.path(), args);
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("no regression"), std::string::npos);
  std::ofstream(dir / "b.json")
      << R"({"metrics": {"success_rate": {"value": 100, "better": "higher", "tolerance": 10},
                         "correct_entries": {"value": 4, "better": "higher", "tolerance": 0}}})";
  r = rownav(dir.path(), args);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.out.find("REGRESSION success_rate: value 50, baseline 100, tolerance 10"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("REGRESSION correct_entries"), std::string::npos) << r.out;
  r = rownav(dir.path(), args + " --update-baseline");
  EXPECT_EQ(r.code, 0) << r.err;
  r = rownav(dir.path(), args);
  EXPECT_EQ(r.code, 0) << r.out;
}

TEST(BenchCli, BadScenarioAndFailingCell) {
  TempDir dir("bench_cli");
  const std::string runner = test::write_fake_runner(dir.path()).string();
  test::write_test_scenario(dir.path(), "[pearl]", "[1]", "    colour: red\n");
  Result r = rownav(dir.path(), "bench --scenario scenario.yaml --runner " + runner);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("scenario.yaml:14:5: unknown key 'colour'"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1);
  test::write_test_scenario(dir.path(), "[pearl, broken]", "[1]");
  r = rownav(dir.path(), "bench --scenario scenario.yaml --out out --runner " + runner);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.out.find("failed cell f1_broken_"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "out/tables.md"));
}

}  // namespace
}  // namespace rownav
