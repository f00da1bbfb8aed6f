#include "rownav/io/localize_setup.hpp"

#include "rownav/io/yaml_config.hpp"

namespace rownav::io {
namespace {

localize::DriveModel drive_model(core::DriveKind kind) {
  switch (kind) {
    case core::DriveKind::differential:
      return localize::DriveModel::differential;
    case core::DriveKind::ackermann:
      return localize::DriveModel::ackermann;
    case core::DriveKind::skid_steer:
      break;
  }
  return localize::DriveModel::skid_steer;
}

}  // namespace

localize::LocalizerConfig localizer_config_for(const core::RobotSpec& robot, int ticks_per_rev) {
  localize::LocalizerConfig c;
  auto& o = c.odometry;
  o.model = drive_model(robot.drive);
  o.track_width = robot.track_width;
  o.wheel_radius = robot.wheel_radius;
  o.wheelbase = robot.wheelbase;
  o.ticks_per_rev = ticks_per_rev;
  // Bertoglio 2023 eq. (2): the robot file's calibration where it gives one, else the nominal
  // (ideal) x_ICR = track / 2, alpha = 1.
  o.x_icr = robot.odometry_x_icr > 0.0 ? robot.odometry_x_icr : 0.5 * robot.track_width;
  o.alpha = robot.odometry_alpha;
  c.validate();
  return c;
}

localize::LocalizerConfig load_localizer_config(const std::filesystem::path& file) {
  return load_config<localize::LocalizerConfig>(file);
}

}  // namespace rownav::io
