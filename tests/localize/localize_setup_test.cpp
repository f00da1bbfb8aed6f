#include "rownav/io/localize_setup.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "rownav/io/yaml_config.hpp"
#include "rownav/sim/robot.hpp"
#include "rownav/sim/simulator.hpp"

namespace rownav::io {
namespace {

TEST(LocalizeSetup, NominalParametersNotTrueOnes) {
  sim::RobotConfig robot;  // skid-steer, true x_icr 0.40, alpha 0.9
  robot.track_width = 0.7;
  sim::SimConfig sim;
  sim.encoders.ticks_per_rev = 1024;
  const auto c = localizer_config_for(robot, sim.encoders.ticks_per_rev);
  EXPECT_EQ(c.odometry.model, localize::DriveModel::skid_steer);
  EXPECT_DOUBLE_EQ(c.odometry.track_width, 0.7);
  EXPECT_DOUBLE_EQ(c.odometry.x_icr, 0.35);
  EXPECT_DOUBLE_EQ(c.odometry.alpha, 1.0);
  EXPECT_EQ(c.odometry.ticks_per_rev, 1024);
  robot.drive = sim::DriveKind::ackermann;
  EXPECT_EQ(localizer_config_for(robot, sim.encoders.ticks_per_rev).odometry.model,
            localize::DriveModel::ackermann);
}

TEST(LocalizeSetup, RobotFilesOdometryCalibrationReplacesTheNominalParameters) {
  sim::RobotConfig robot;
  robot.track_width = 0.7;
  robot.odometry_x_icr = 0.41;
  robot.odometry_alpha = 0.88;
  const auto c = localizer_config_for(robot, 1024);
  EXPECT_DOUBLE_EQ(c.odometry.x_icr, 0.41);
  EXPECT_DOUBLE_EQ(c.odometry.alpha, 0.88);
  robot.odometry_alpha = 0.0;
  EXPECT_THROW(robot.validate(), std::invalid_argument);
}

TEST(LocalizeSetup, ShippedDefaultFileEqualsDefaults) {
  const auto file = std::filesystem::path(ROWNAV_SOURCE_DIR) / "config/localize/default.yaml";
  const auto c = load_localizer_config(file);
  const YAML::Node a = encode_config(c), b = encode_config(localize::LocalizerConfig{});
  EXPECT_EQ(YAML::Dump(a), YAML::Dump(b));
}

}  // namespace
}  // namespace rownav::io
