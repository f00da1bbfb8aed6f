#pragma once
/// @file setup.hpp Loading the field / robot / sensors / path files the commands take.
#include <Eigen/Geometry>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rownav/sim/field.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/robot.hpp"
#include "rownav/sim/scripted_path.hpp"
#include "rownav/sim/simulator.hpp"

namespace rownav::app {

/// Everything a simulated drive needs.
struct Setup {
  sim::FieldConfig field_config;
  sim::Field field;
  sim::RobotConfig robot;
  sim::SimConfig sensors;
  sim::PathConfig path;
};

/// `--field` check: an existing file or a zoo reference (empty string when valid).
std::string check_field_arg(const std::string& value);
sim::RobotConfig load_robot(const std::optional<std::filesystem::path>& file);
sim::SimConfig load_sensors(const std::optional<std::filesystem::path>& file,
                            const std::string& lidar_preset_override);
sim::PathConfig load_path(const std::optional<std::filesystem::path>& file);

/// T_base_lidar from --lidar-mount x,y,z,roll_deg,pitch_deg,yaw_deg (Rz(yaw) Ry(pitch) Rx(roll)).
Eigen::Isometry3d mount_transform(const std::vector<double>& m);

/// Starting pose: on the path's first point, facing its second.
core::Pose2 path_start(const std::vector<sim::PathPoint>& path);

}  // namespace rownav::app
