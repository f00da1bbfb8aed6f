// Running benchmark cells through a fake runner: resume, parallel jobs, a failing cell.
#include "rownav/io/bench_runner.hpp"
#include "rownav/io/safe_output.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "common/bench_fake.hpp"
#include "common/cli_runner.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::TempDir;

int count_lines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

TEST(BenchRunner, ResumeSkipsCellsWithSummary) {
  TempDir dir("bench");
  const auto cells =
      expand_scenario(load_scenario(test::write_test_scenario(dir.path(), "[pearl]", "[1, 2, 4]")));
  ASSERT_EQ(cells.size(), 3u);
  const fs::path out = dir / "out";
  fs::create_directories(cell_dir(out, cells[1]));
  std::ofstream(out / std::string(kOutputMarker)) << "rownav bench\n";  // an earlier bench's folder
  std::ofstream(cell_dir(out, cells[1]) / "summary.json") << "{\"success\": true}\n";
  fs::create_directories(cell_dir(out, cells[2]));  // a killed run: no summary.json
  std::ostringstream progress;
  BenchRunnerOptions o{test::write_fake_runner(dir.path()), 2, &progress};
  const auto r = run_cells(cells, out, o);
  EXPECT_EQ(r.count(CellStatus::ran), 2);
  EXPECT_EQ(r.count(CellStatus::resumed), 1);
  EXPECT_EQ(r.cells[1].status, CellStatus::resumed);
  const std::string calls = read_file(dir / "invocations.txt");
  EXPECT_EQ(calls.find("pearl 2"), std::string::npos) << calls;
  EXPECT_EQ(count_lines(calls), 2);
  EXPECT_NE(progress.str().find(cells[1].id + ": resumed"), std::string::npos) << progress.str();
  EXPECT_TRUE(fs::exists(cell_dir(out, cells[2]) / "summary.json"));
  EXPECT_NE(read_file(cell_dir(out, cells[0]) / "log.txt").find("'--seed' '1'"), std::string::npos);
  // Everything done: a second run starts nothing.
  const auto again = run_cells(cells, out, o);
  EXPECT_EQ(again.count(CellStatus::resumed), 3);
  EXPECT_EQ(count_lines(read_file(dir / "invocations.txt")), 2);
}

TEST(BenchRunner, AUsersNonEmptyFolderIsRefusedAndKept) {
  TempDir dir("bench");
  const auto cells =
      expand_scenario(load_scenario(test::write_test_scenario(dir.path(), "[pearl]", "[1]")));
  std::ofstream(dir / "notes.txt") << "mine";
  BenchRunnerOptions o{test::write_fake_runner(dir.path()), 1, nullptr};
  EXPECT_THROW(run_cells(cells, dir.path(), o), std::runtime_error);
  EXPECT_EQ(read_file(dir / "notes.txt"), "mine");
  EXPECT_FALSE(fs::exists(dir / "runs"));
}

TEST(BenchRunner, FailingCellIsReportedOthersComplete) {
  TempDir dir("bench");
  const auto cells = expand_scenario(
      load_scenario(test::write_test_scenario(dir.path(), "[pearl, broken, ruby]", "[1, 3]")));
  ASSERT_EQ(cells.size(), 6u);
  std::ostringstream progress;
  const auto r = run_cells(cells, dir / "out", {test::write_fake_runner(dir.path()), 3, &progress});
  EXPECT_EQ(r.count(CellStatus::failed), 2);
  EXPECT_EQ(r.count(CellStatus::ran), 4);  // seed 3 (mission failed, exit 1) still has a summary
  EXPECT_FALSE(r.interrupted);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const bool broken = cells[i].detector == "broken";
    EXPECT_EQ(r.cells[i].status, broken ? CellStatus::failed : CellStatus::ran) << cells[i].id;
    EXPECT_EQ(fs::exists(cell_dir(dir / "out", cells[i]) / "summary.json"), !broken);
  }
  const auto log = read_file(cell_dir(dir / "out", cells[2]) / "log.txt");
  EXPECT_NE(log.find("unknown detector broken"), std::string::npos) << log;
  EXPECT_NE(progress.str().find("FAILED (exit 2, no summary.json)"), std::string::npos);
  EXPECT_NE(progress.str().find("[6/6, 2 failed, ETA"), std::string::npos) << progress.str();
}

TEST(BenchRunner, MissingRunnerThrows) {
  TempDir dir("bench");
  EXPECT_THROW(run_cells({}, dir / "out", {dir / "nope", 1, nullptr}), std::runtime_error);
}

}  // namespace
}  // namespace rownav::io
