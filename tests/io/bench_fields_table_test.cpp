// Issue 10: the `fields` tables group zoo runs by band, other runs by field, and list failures.
#include "rownav/io/bench_fields_table.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rownav::io {
namespace {

CellResult run(const std::string& field, bool has_summary = true) {
  CellResult r;
  r.cell.id = field + "-id";
  r.cell.field = field;
  r.cell.tables = {BenchTable::fields};
  if (has_summary) r.summary = RunSummary{};
  return r;
}

CellResult with(CellResult r, bool success, int served, int planned, int crushed,
               const std::string& reason) {
  r.summary->numbers = {
      {"success", success ? 1.0 : 0.0},   {"corridors_served", served},
      {"corridors_planned", planned},     {"plants_crushed", crushed},
      {"in_row_mean_displacement", 0.02}, {"in_row_max_displacement", success ? 0.05 : 0.2}};
  r.summary->strings = {{"stop_reason", reason}};
  return r;
}

TEST(BenchFieldsTable, ZooRunsGroupByBandFilesByNameFailuresAreListed) {
  // zoo:1:0 and zoo:1:5 are both vineyard_narrow (band i % 5); zoo:1:4 a row crop.
  const std::vector<CellResult> runs = {
      with(run("zoo:1:0"), true, 5, 5, 0, "done"), with(run("zoo:1:5"), false, 2, 5, 0, "obstacle"),
      with(run("zoo:1:4"), false, 0, 5, 7, "perception_lost"),
      with(run("config/fields/closed_loop_narrow.yaml"), true, 5, 5, 0, "done"),
      run("config/fields/orchard.yaml", false)};
  std::vector<ResultTable> out;
  add_fields_tables(runs, out);
  ASSERT_EQ(out.size(), 2u);
  const ResultTable& t = out[0];
  ASSERT_EQ(t.key, "fields");
  ASSERT_EQ(t.rows.size(), 3u);  // orchard.yaml left no summary: only in the failures
  EXPECT_EQ(t.rows[0].labels[0], "zoo vineyard_narrow");
  EXPECT_EQ(*t.rows[0].values[0], 2.0);         // runs
  EXPECT_EQ(*t.rows[0].values[1], 50.0);        // success [%]
  EXPECT_EQ(*t.rows[0].values[2], 70.0);        // 7 of 10 corridors
  EXPECT_GT(*t.rows[0].values[3], 1.0);         // spacing min of the band's fields
  EXPECT_DOUBLE_EQ(*t.rows[0].values[6], 0.2);  // displacement max over runs
  EXPECT_EQ(t.rows[1].labels[0], "zoo row_crop");
  EXPECT_EQ(*t.rows[1].values[7], 7.0);  // plants crushed (sum)
  EXPECT_EQ(t.rows[2].labels[0], "closed_loop_narrow");
  EXPECT_FALSE(t.rows[2].values[3].has_value());  // no zoo spacing for a file
  const ResultTable& f = out[1];
  ASSERT_EQ(f.rows.size(), 3u);
  EXPECT_EQ(f.rows[0].labels[1], "obstacle");
  EXPECT_EQ(f.rows[1].labels[1], "perception_lost");
  EXPECT_EQ(f.rows[2].labels[1], "no summary");
  EXPECT_EQ(f.rows[2].values.size(), f.value_columns.size());
}

TEST(BenchFieldsTable, NoRunFeedingTheTableAddsNothing) {
  CellResult r = with(run("zoo:1:0"), true, 5, 5, 0, "done");
  r.cell.tables = {BenchTable::timing};
  std::vector<ResultTable> out;
  add_fields_tables({r}, out);
  EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace rownav::io
