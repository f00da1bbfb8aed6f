// The robot file as the stack knows it (core::RobotSpec, read without the simulator) and the
// NavStackConfig derived from it: the ROS node and `rownav run` must derive the same footprint
// and limits from the same file (issue 14).
#include "rownav/io/nav_stack_setup.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/field_names.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/sim/robot.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

using Names = test::NameCollector;

TEST(NavStackSetup, TheSkippedRobotKeysAreExactlyTheSimulatorsOnes) {
  sim::RobotConfig robot;
  Names sim_keys;
  sim::RobotConfig::simulation_fields(robot, sim_keys);
  ASSERT_EQ(sim_keys.names.size(), kSimulatorRobotKeys.size());
  for (std::size_t i = 0; i < kSimulatorRobotKeys.size(); ++i)
    EXPECT_EQ(sim_keys.names[i], kSimulatorRobotKeys[i]);
  // A robot file is the spec's keys plus those: no other key is in sim::RobotConfig.
  Names spec_keys, all_keys;
  core::RobotSpec::fields(robot, spec_keys);
  sim::RobotConfig::fields(robot, all_keys);
  EXPECT_EQ(all_keys.names.size(), spec_keys.names.size() + sim_keys.names.size());
}

TEST(NavStackSetup, EveryShippedRobotReadsAsTheSameSpecWithoutTheSimulator) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(fs::path(ROWNAV_SOURCE_DIR) / "config/robots")) {
    if (e.path().extension() != ".yaml") continue;
    ++n;
    const auto robot = load_config<sim::RobotConfig>(e.path());
    const core::RobotSpec spec = load_robot_spec(e.path());
    navigate::NavStackConfig from_sim, from_spec;
    nav_stack_robot(from_sim, robot, 1024, 10.0);
    nav_stack_robot(from_spec, spec, 1024, 10.0);
    EXPECT_EQ(spec.name, robot.name) << e.path();
    EXPECT_EQ(spec.drive, robot.drive) << e.path();
    EXPECT_DOUBLE_EQ(from_spec.robot.width, from_sim.robot.width) << e.path();
    EXPECT_DOUBLE_EQ(from_spec.robot.base_to_front, from_sim.robot.base_to_front) << e.path();
    EXPECT_EQ(from_spec.robot.turn.can_turn_in_place, from_sim.robot.turn.can_turn_in_place) << e.path();
    EXPECT_DOUBLE_EQ(from_spec.limits.max_speed, from_sim.limits.max_speed) << e.path();
    EXPECT_DOUBLE_EQ(from_spec.limits.min_turn_radius, from_sim.limits.min_turn_radius);
    EXPECT_DOUBLE_EQ(from_spec.localizer.odometry.track_width,
                     from_sim.localizer.odometry.track_width);
  }
  EXPECT_GE(n, 4);
}

TEST(NavStackSetup, ARobotSpecStillRefusesUnknownKeysAndBadValues) {
  const fs::path dir = fs::temp_directory_path() / "rownav_robot_spec_test";
  fs::create_directories(dir);
  const fs::path typo = dir / "typo.yaml", bad = dir / "bad.yaml";
  std::ofstream(typo) << "drive: skid_steer\ntrack_widht: 0.5\nslip_noise: 0.02\n";
  std::ofstream(bad) << "width: -1\nx_icr: 0.3\n";
  EXPECT_THROW(load_robot_spec(typo), InputError);
  try {
    load_robot_spec(bad);
    ADD_FAILURE() << "a negative width was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("width"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(NavStackSetup, LimitsAndFootprintComeFromTheSpecAndTheSweepFromTheLidarRate) {
  core::RobotSpec spec;
  spec.drive = core::DriveKind::ackermann;
  spec.wheelbase = 1.2;
  spec.max_steer_deg = 45.0;
  spec.width = 0.8;
  spec.max_speed = 0.7;
  navigate::NavStackConfig nav;
  nav_stack_robot(nav, spec, 2048, 20.0);
  EXPECT_DOUBLE_EQ(nav.robot.width, 0.8);
  EXPECT_FALSE(nav.robot.turn.can_turn_in_place);
  EXPECT_NEAR(nav.limits.min_turn_radius, 1.2, 1e-12);  // wheelbase / tan(45 deg)
  EXPECT_DOUBLE_EQ(nav.limits.max_speed, 0.7);
  EXPECT_EQ(nav.localizer.odometry.ticks_per_rev, 2048);
  EXPECT_DOUBLE_EQ(nav.stack.sweep_period, 0.05);
}

}  // namespace
}  // namespace rownav::io
