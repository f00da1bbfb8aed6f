#include "rownav/io/run_report.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/cli_runner.hpp"
#include "rownav/io/run_metrics.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/field_truth.hpp"

namespace rownav::io {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) out.push_back(cell);
  return out;
}

TEST(RunReport, TrajectoryCsvHoldsThePoseTheStackBelievedBesideTheTruth) {
  sim::FieldConfig f;
  f.vineyard.rows = 3, f.vineyard.row_length = 10.0, f.vineyard.row_spacing = 2.0;
  const sim::Field field = sim::generate_field(f);
  const sim::FieldTruth truth(field);
  RunResult run;
  for (int i = 0; i < 5; ++i) {
    RunSample s;
    s.stamp = 0.1 * i;
    s.T_world_base = core::Pose2(-1.0 + 0.5 * i, 1.0, 0.0);
    s.T_odom_base = core::Pose2(0.55 * i, 0.01 * i, 0.002 * i);  // odometry 10 % long, drifting
    run.samples.push_back(s);
  }
  test::TempDir dir("run_report");
  write_run_report(dir.path(), run, summarize(run, truth), RunNames{}, field);
  std::ifstream in(dir.path() / "trajectory.csv");
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  const auto header = split(line);
  const auto col = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  ASSERT_LT(col("odom_theta"), header.size());
  for (const auto& s : run.samples) {
    ASSERT_TRUE(std::getline(in, line));
    const auto cells = split(line);
    ASSERT_EQ(cells.size(), header.size());
    EXPECT_NEAR(std::stod(cells[col("x")]), s.T_world_base.x, 1e-9);
    EXPECT_NEAR(std::stod(cells[col("odom_x")]), s.T_odom_base.x, 1e-9);
    EXPECT_NEAR(std::stod(cells[col("odom_y")]), s.T_odom_base.y, 1e-9);
    EXPECT_NEAR(std::stod(cells[col("odom_theta")]), s.T_odom_base.theta, 1e-9);
  }
}

TEST(RunReport, RowEndsCsvListsEachEstimatedEndBesideItsTrueEnd) {
  sim::FieldConfig f;
  f.vineyard.rows = 3, f.vineyard.row_length = 10.0, f.vineyard.row_spacing = 2.0;
  const sim::Field field = sim::generate_field(f);
  const sim::FieldTruth truth(field);
  const auto& row = field.rows[1];
  const Eigen::Vector2d out = (row.end() - row.start()).normalized();
  RunResult run;
  run.row_ends_world = {row.end() + 0.2 * out, row.start() + 0.05 * out};
  test::TempDir dir("run_report_ends");
  write_run_report(dir.path(), run, summarize(run, truth), RunNames{}, field);
  std::ifstream in(dir.path() / "row_ends.csv");
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, "x,y,true_x,true_y,error,along,across");
  const std::vector<std::pair<Eigen::Vector2d, double>> want{{row.end(), 0.2},
                                                             {row.start(), -0.05}};
  for (const auto& [end, along] : want) {
    ASSERT_TRUE(std::getline(in, line));
    const auto c = split(line);
    ASSERT_EQ(c.size(), 7u);
    EXPECT_NEAR(std::stod(c[2]), end.x(), 1e-6);
    EXPECT_NEAR(std::stod(c[3]), end.y(), 1e-6);
    EXPECT_NEAR(std::stod(c[4]), std::abs(along), 1e-6);
    EXPECT_NEAR(std::stod(c[5]), along, 1e-6);
  }
  EXPECT_FALSE(std::getline(in, line));
}

TEST(RunReport, NoRowEndEstimatedWritesNoRowEndsCsv) {
  sim::FieldConfig f;
  f.vineyard.rows = 3, f.vineyard.row_length = 10.0, f.vineyard.row_spacing = 2.0;
  const sim::Field field = sim::generate_field(f);
  const sim::FieldTruth truth(field);
  test::TempDir dir("run_report_no_ends");
  write_run_report(dir.path(), RunResult{}, summarize(RunResult{}, truth), RunNames{}, field);
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "summary.json"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "row_ends.csv"));
}

}  // namespace
}  // namespace rownav::io
