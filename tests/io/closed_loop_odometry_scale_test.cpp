// The wheel odometry's alpha learnt online from the LiDAR (navigate::StackConfig::odometry_scale,
// Bertoglio 2023 eq. (2); issue 11), in closed loop: the simulator drives each robot with its
// true alpha (skid_steer 0.90, row_crop_small 0.92) while the stack's odometry starts from the
// nominal 1 (10 % and 8.7 % long). Asserted: the mission succeeds and the alpha the stack ends
// with is within 0.02 of the simulator's (measured: 0.890 in the narrow vineyard, 0.910 in maize,
// both about 1 % low; the sweep is not deskewed, BENCHMARK.md). Not asserted: the row-end error,
// which rises with right odometry (0.05 -> 0.12 m in the narrow vineyard: the stack's row end is
// the canopy's end, 0.10 m past the end post, which the 10 % long odometry used to hide).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "rownav/io/closed_loop_runner.hpp"
#include "rownav/io/controller_registry.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/io/field_builder.hpp"
#include "rownav/io/mission_io.hpp"
#include "rownav/io/run_metrics.hpp"
#include "rownav/io/sim_setup.hpp"
#include "rownav/io/tracker_registry.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/sim/field_zoo.hpp"

namespace rownav::io {
namespace {

const std::filesystem::path kConfig = std::filesystem::path(ROWNAV_SOURCE_DIR) / "config";

struct Outcome {
  RunSummary summary;
  double true_alpha = 1.0;
};

Outcome run(const sim::FieldConfig& fc, const std::string& robot, const std::string& crop,
            bool estimate) {
  const sim::Field field = build_field(fc, kConfig / "fields");
  ClosedLoopSetup s;
  s.field = &field;
  s.robot = load_config<sim::RobotConfig>(kConfig / "robots" / (robot + ".yaml"));
  s.sensors = load_sim_config(kConfig / "sensors" / "os1_16.yaml");
  s.sensors.seed = 1;
  s.mission = load_mission(kConfig / "missions" / "serve_all.yaml");
  s.nav = load_config<navigate::NavStackConfig>(kConfig / "navigate" / (crop + ".yaml"));
  s.nav.stack.odometry_scale.enabled = estimate;
  s.detect_config = kConfig / "detect" / (crop + ".yaml");
  s.detector = default_detector(s.detect_config);
  s.make_tracker = [] { return make_tracker("model_filter", ""); };
  s.make_controller = [] { return make_controller("stanley", ""); };
  s.time_limit = 600.0;
  return {summarize(run_closed_loop(s), sim::FieldTruth(field), s.mission.block), s.robot.alpha};
}

Outcome run(const std::string& field_name, const std::string& robot, const std::string& crop,
            bool estimate) {
  return run(load_config<sim::FieldConfig>(kConfig / "fields" / (field_name + ".yaml")), robot,
             crop, estimate);
}

TEST(ClosedLoopOdometryScale, TheStackLearnsEachRobotsAlphaFromItsLidarWhileServingTheField) {
  struct Case {
    std::string field, robot, crop;
  };
  for (const Case& c : {Case{"closed_loop_narrow", "skid_steer", "vineyard"},
                        Case{"closed_loop_maize", "row_crop_small", "row_crop"}}) {
    const Outcome o = run(c.field, c.robot, c.crop, true);
    EXPECT_TRUE(o.summary.success) << c.field << ": " << o.summary.stop_reason;
    EXPECT_GE(o.summary.odometry_scale_samples, 20) << c.field;
    EXPECT_NEAR(o.summary.odometry_alpha, o.true_alpha, 0.02) << c.field;
  }
}

TEST(ClosedLoopOdometryScale, ARandomNarrowVineyardIsServedThroughEntriesBesideTheEndPlants) {
  // zoo:1:5 (1.64 m rows, slopes 5.9 / 3.8 deg). With alpha learnt, the robot entered its fifth
  // corridor 0.10-0.12 m off centre and stopped `obstacle` (10 points of the end plants' canopy at
  // its flank, |y| 0.21-0.30 m), 4 of 5 corridors, until the canopy reach measured in the rows
  // was also applied while entering (NavStack::drop_row_canopy).
  const Outcome o = run(sim::zoo_field(5, 1), "skid_steer", "vineyard", true);
  EXPECT_TRUE(o.summary.success) << o.summary.stop_reason;
  EXPECT_EQ(o.summary.corridors_served, o.summary.corridors_planned);
  EXPECT_NEAR(o.summary.odometry_alpha, o.true_alpha, 0.02);
}

TEST(ClosedLoopOdometryScale, OffTheOdometryKeepsTheRobotFilesAlpha) {
  const Outcome o = run("closed_loop_narrow", "skid_steer", "vineyard", false);
  EXPECT_EQ(o.summary.odometry_scale_samples, 0);
  EXPECT_DOUBLE_EQ(o.summary.odometry_alpha, 1.0);
}

}  // namespace
}  // namespace rownav::io
