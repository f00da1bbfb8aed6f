// Paper tables from hand-written summary.json files, their output files, and the baseline gate.
#include "rownav/io/bench_tables.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "common/cli_runner.hpp"
#include "rownav/io/bench_baseline.hpp"
#include "rownav/io/bench_report.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::TempDir;

BenchCell cell(const std::string& id, const std::string& det, const std::string& trk,
               std::vector<BenchTable> tables) {
  BenchCell c;
  c.id = id;
  c.field = "bench/fields/weeds_some.yaml";
  c.detector = det;
  c.tracker = trk;
  c.controller = "lookahead_pid";
  c.tables = std::move(tables);
  return c;
}

// Three runs of pearl+model_filter (one without summary), one of ruby+none.
std::vector<CellResult> hand_written(const fs::path& out) {
  const std::vector<std::pair<BenchCell, std::string>> runs = {
      {cell("a", "pearl", "model_filter", {BenchTable::malavazi_004, BenchTable::nehme_000}),
       R"({"success": true, "plants_crushed": 0, "path_length_ratio_mean": 1.02,
           "path_length_ratio_max": 1.05, "path_length_ratio_min": 1.0, "in_row_lateral_rmse": 0.1,
           "per_corridor": [{"corridor": 0, "lateral_rmse": 0.1}, {"corridor": 1, "lateral_rmse": 0.3}]})"},
      {cell("b", "pearl", "model_filter", {BenchTable::malavazi_004, BenchTable::nehme_000}),
       R"({"success": true, "plants_crushed": 2, "path_length_ratio_mean": 1.04,
           "path_length_ratio_max": 1.09, "path_length_ratio_min": null, "in_row_lateral_rmse": 0.3,
           "per_corridor": [{"corridor": 0, "lateral_rmse": 0.2}]})"},
      {cell("c", "pearl", "model_filter", {BenchTable::malavazi_004}), ""},
      {cell("d", "ruby", "none", {BenchTable::malavazi_004, BenchTable::timing}),
       R"({"success": false, "plants_crushed": 0, "frame_latency_median_ms": 3.0,
           "sim_time": 100, "wall_time": 20})"}};
  std::vector<BenchCell> cells;
  for (const auto& [c, text] : runs) {
    cells.push_back(c);
    if (text.empty()) continue;
    fs::create_directories(cell_dir(out, c));
    std::ofstream(cell_dir(out, c) / "summary.json") << text;
  }
  return collect_results(cells, out);
}

const ResultTable* find(const std::vector<ResultTable>& t, const std::string& key) {
  for (const auto& x : t)
    if (x.key == key) return &x;
  return nullptr;
}

TEST(BenchTables, MalavaziRowsAggregateRuns) {
  TempDir dir("bench");
  const auto tables = build_tables(hand_written(dir.path()));
  const auto* t = find(tables, "malavazi_004_weeds_some");
  ASSERT_NE(t, nullptr);
  ASSERT_EQ(t->rows.size(), 2u);
  EXPECT_EQ(t->rows[0].labels, (std::vector<std::string>{"pearl", "filtered (model_filter)"}));
  const auto& v = t->rows[0].values;  // runs, success, no crush, ratio mean / max / min
  EXPECT_EQ(v[0], 2.0);
  EXPECT_DOUBLE_EQ(*v[1], 100.0);
  EXPECT_DOUBLE_EQ(*v[2], 50.0);
  EXPECT_DOUBLE_EQ(*v[3], 1.03);
  EXPECT_DOUBLE_EQ(*v[4], 1.09);
  EXPECT_DOUBLE_EQ(*v[5], 1.0);
  EXPECT_EQ(t->rows[1].labels[1], "unfiltered");
  EXPECT_DOUBLE_EQ(*t->rows[1].values[1], 0.0);
  EXPECT_FALSE(t->rows[1].values[3].has_value());  // never measured: n/a
}

TEST(BenchTables, NehmePerCorridorAndTiming) {
  TempDir dir("bench");
  const auto tables = build_tables(hand_written(dir.path()));
  const auto* n = find(tables, "nehme_000_weeds_some");
  ASSERT_NE(n, nullptr);
  ASSERT_EQ(n->rows.size(), 3u);  // corridors 0, 1, all rows
  EXPECT_DOUBLE_EQ(*n->rows[0].values[0], 0.15);
  EXPECT_DOUBLE_EQ(*n->rows[1].values[0], 0.3);
  EXPECT_DOUBLE_EQ(*n->rows[2].values[0], 0.2);
  const auto* t = find(tables, "timing");
  ASSERT_NE(t, nullptr);
  EXPECT_DOUBLE_EQ(*t->rows[0].values[1], 3.0);
  EXPECT_FALSE(t->rows[0].values[2].has_value());
  EXPECT_DOUBLE_EQ(*t->rows[0].values[3], 5.0);
  EXPECT_EQ(find(tables, "lan_001"), nullptr);  // no run feeds it
}

// Issue 11: the 003 protocol at 0.8 and at 2 m/s (robot files skid_steer / skid_steer_2ms) is
// two rows of each table, not one mean over both speeds; Table II finds the paper's figures by
// the policy.
TEST(BenchTables, BertoglioRowsAreSplitByRobotFileSoSpeedsDoNotMix) {
  TempDir dir("bench");
  std::vector<BenchCell> cells;
  const std::vector<std::pair<std::string, std::string>> runs = {
      {"config/robots/skid_steer.yaml",
       R"({"success": true, "speed_max": 0.8, "in_row_mean_displacement": 0.03,
           "turn_row_end_error_mean": 0.2})"},
      {"bench/configs/skid_steer_2ms.yaml",
       R"({"success": false, "speed_max": 1.9, "in_row_mean_displacement": 0.05,
           "turn_row_end_error_mean": 0.4})"}};
  for (const auto& [robot, text] : runs) {
    BenchCell c = cell(robot, "cone_rect", "none", {BenchTable::bertoglio_003});
    c.id = fs::path(robot).stem().string();
    c.robot = robot;
    c.row_end_policy = "nearest";
    fs::create_directories(cell_dir(dir.path(), c));
    std::ofstream(cell_dir(dir.path(), c) / "summary.json") << text;
    cells.push_back(c);
  }
  const auto tables = build_tables(collect_results(cells, dir.path()));
  const auto* t1 = find(tables, "bertoglio_003_table1");
  ASSERT_NE(t1, nullptr);
  ASSERT_EQ(t1->rows.size(), 2u);
  EXPECT_EQ(t1->rows[0].labels,
            (std::vector<std::string>{"weeds_some", "skid_steer", "cone_rect+none+lookahead_pid"}));
  EXPECT_EQ(t1->rows[1].labels[1], "skid_steer_2ms");
  const auto& slow = t1->rows[0].values;  // runs, success, top speed, displacement mean
  const auto& fast = t1->rows[1].values;
  EXPECT_DOUBLE_EQ(*slow[1], 100.0);
  EXPECT_DOUBLE_EQ(*fast[1], 0.0);
  EXPECT_DOUBLE_EQ(*slow[2], 0.8);
  EXPECT_DOUBLE_EQ(*fast[2], 1.9);
  EXPECT_DOUBLE_EQ(*fast[3], 0.05);
  const auto* t2 = find(tables, "bertoglio_003_table2");
  ASSERT_NE(t2, nullptr);
  ASSERT_EQ(t2->rows.size(), 2u);
  EXPECT_EQ(t2->rows[1].labels,
            (std::vector<std::string>{"weeds_some", "skid_steer_2ms", "nearest"}));
  EXPECT_DOUBLE_EQ(*t2->rows[1].values[3], 0.4);
  EXPECT_DOUBLE_EQ(*t2->rows[1].values[6], 0.205);  // the paper's Nearest mean
}

TEST(BenchTables, FilesShowNaAndNull) {
  TempDir dir("bench");
  const auto files = write_tables(dir / "out", "test", build_tables(hand_written(dir.path())));
  const std::string md = read_file(dir / "out/tables.md");
  EXPECT_NE(md.find("| ruby | unfiltered | 1 | 0 | 0 | n/a | n/a | n/a |"), std::string::npos)
      << md;
  const std::string js = read_file(dir / "out/tables.json");
  EXPECT_NE(js.find("null"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "out/plots/malavazi_004_weeds_some.svg"));
  EXPECT_GE(files.size(), 3u);
}

TEST(BenchBaseline, GatePassesWhenBeatenAndNamesRegressions) {
  TempDir dir("bench");
  const auto now = gate_metrics(hand_written(dir.path()));
  EXPECT_DOUBLE_EQ(*now.at("success_rate"), 200.0 / 3.0);
  EXPECT_EQ(now.at("failed_cells"), 1.0);
  std::ofstream(dir / "b.json") << R"({"metrics": {
      "success_rate": {"value": 60, "better": "higher", "tolerance": 1},
      "plants_crushed": {"value": 2, "better": "lower", "tolerance": 0},
      "in_row_mean_displacement": {"value": null, "better": "lower", "tolerance": 0}}})";
  EXPECT_TRUE(check_baseline(read_baseline(dir / "b.json"), now).empty());
  std::ofstream(dir / "b.json") << R"({"metrics": {
      "success_rate": {"value": 90, "better": "higher", "tolerance": 5, "relative_tolerance": 0.1},
      "plants_crushed": {"value": 1, "better": "lower", "tolerance": 0}}})";
  const auto lines = check_baseline(read_baseline(dir / "b.json"), now);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "plants_crushed: value 2, baseline 1, tolerance 0 (lower is better)");
  EXPECT_EQ(lines[1], "success_rate: value 66.667, baseline 90, tolerance 14 (higher is better)");
  const Baseline updated = updated_baseline(read_baseline(dir / "b.json"), now);
  EXPECT_EQ(updated.metrics.at("success_rate").tolerance, 5.0);
  EXPECT_TRUE(check_baseline(updated, now).empty());
  std::ofstream(dir / "b.json") << R"({"metrics": {"success_rate": {"valu": 1}}})";
  EXPECT_THROW(read_baseline(dir / "b.json"), InputError);
}

}  // namespace
}  // namespace rownav::io
