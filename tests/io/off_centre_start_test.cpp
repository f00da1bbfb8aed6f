// The robot placed off the corridor centre line and yawed (brief: "test with ... the robot
// off-centre and yawed"): perturbed_start moves the start pose in its own frame, and the default
// stack (hough_skew + model_filter + stanley, OS1-16) still serves the narrow vineyard of the
// closed-loop matrix, shrunk to 4 rows x 20 m, from seeded random starts: offset uniform in
// +-0.15 m (a quarter of the 0.6 m robot's width; the corridor leaves it ~0.2 m a side), yaw
// uniform in +-10 deg. The issue-5 accuracy targets are asserted over the whole run, so the
// start's convergence counts against them. The start is the runner's: 1.5 m before the entrance;
// at the row start (lead-in 0) the start offset is itself an in-row displacement.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>

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

TEST(PerturbedStart, MovesToTheStartsLeftAndTurnsCounterClockwise) {
  const core::Pose2 p = perturbed_start({1.0, 2.0, 0.0}, 0.3, 0.1);
  EXPECT_NEAR(p.x, 1.0, 1e-12);
  EXPECT_NEAR(p.y, 2.3, 1e-12);
  EXPECT_NEAR(p.theta, 0.1, 1e-12);
}

TEST(PerturbedStart, OffsetIsAcrossTheStartHeading) {
  // Facing +y, the start's left is -x.
  const core::Pose2 p = perturbed_start({0.0, 0.0, std::numbers::pi / 2.0}, -0.2, -0.3);
  EXPECT_NEAR(p.x, 0.2, 1e-12);
  EXPECT_NEAR(p.y, 0.0, 1e-12);
  EXPECT_NEAR(p.theta, std::numbers::pi / 2.0 - 0.3, 1e-12);
}

RunSummary run_from(double offset, double yaw, double lead_in = ClosedLoopSetup{}.lead_in) {
  auto fc = load_config<sim::FieldConfig>(kConfig / "fields" / "closed_loop_narrow.yaml");
  fc.vineyard.rows = 4;
  fc.vineyard.row_length = 20.0;
  const sim::Field field = build_field(fc, kConfig / "fields");
  ClosedLoopSetup s;
  s.field = &field;
  s.robot = load_config<sim::RobotConfig>(kConfig / "robots" / "skid_steer.yaml");
  s.sensors = load_sim_config(kConfig / "sensors" / "os1_16.yaml");
  s.mission = load_mission(kConfig / "missions" / "serve_all.yaml");
  s.detect_config = kConfig / "detect" / "vineyard.yaml";
  s.make_tracker = [] { return make_tracker("model_filter", ""); };
  s.make_controller = [] { return make_controller("stanley", ""); };
  s.time_limit = 600.0;
  s.lead_in = lead_in;
  s.start_offset = offset;
  s.start_yaw = yaw;
  return summarize(run_closed_loop(s), sim::FieldTruth(field), s.mission.block);
}

class OffCentreStart : public ::testing::TestWithParam<int> {};

TEST_P(OffCentreStart, ServesTheNarrowVineyardWithinTheIssue5Targets) {
  std::mt19937_64 rng(static_cast<std::uint64_t>(GetParam()));
  const double offset = std::uniform_real_distribution<double>(-0.15, 0.15)(rng);
  const double yaw = core::deg2rad(std::uniform_real_distribution<double>(-10.0, 10.0)(rng));
  const RunSummary s = run_from(offset, yaw);
  SCOPED_TRACE("offset " + std::to_string(offset) + " m, yaw " + std::to_string(yaw) + " rad");
  EXPECT_TRUE(s.success) << s.stop_reason;
  EXPECT_EQ(s.corridors_served, s.corridors_planned);
  EXPECT_EQ(s.correct_entries, s.corridors_planned - 1);
  EXPECT_EQ(s.wrong_entries, 0);
  EXPECT_EQ(s.plants_crushed, 0);
  EXPECT_FALSE(s.collision);
  ASSERT_TRUE(s.in_row_mean_displacement && s.in_row_max_displacement);
  EXPECT_LE(*s.in_row_mean_displacement, 0.03);
  EXPECT_LE(*s.in_row_max_displacement, 0.10);
}

INSTANTIATE_TEST_SUITE_P(Seeds, OffCentreStart, ::testing::Values(1, 2, 3, 4));

TEST(OffCentreStartAtTheRowStart, ConvergesWithoutOvershootingTheStartOffset) {
  // Placed at the head of the row (lead-in 0), 0.15 m off and yawed 10 deg away from the centre:
  // the in-row displacement starts at the offset and must only shrink (measured 0.157 m max,
  // 0.010 m mean; 0.02 m for the yaw's first metres).
  const double offset = 0.15;
  const RunSummary s = run_from(offset, core::deg2rad(10.0), 0.0);
  EXPECT_TRUE(s.success) << s.stop_reason;
  EXPECT_FALSE(s.collision);
  EXPECT_EQ(s.plants_crushed, 0);
  ASSERT_TRUE(s.in_row_mean_displacement && s.in_row_max_displacement);
  EXPECT_GE(*s.in_row_max_displacement, offset - 0.01);  // the start was off-centre
  EXPECT_LE(*s.in_row_max_displacement, offset + 0.02);
  EXPECT_LE(*s.in_row_mean_displacement, 0.03);
}

}  // namespace
}  // namespace rownav::io
