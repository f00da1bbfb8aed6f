#include "setup.hpp"

#include <cmath>

#include "rownav/core/angle.hpp"
#include "rownav/io/field_builder.hpp"
#include "rownav/io/sim_setup.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/sim/field_zoo.hpp"
#include "rownav/sim/lidar_presets.hpp"

namespace rownav::app {

std::string check_field_arg(const std::string& value) {
  if (sim::parse_zoo_ref(value) || std::filesystem::is_regular_file(value)) return {};
  return "File does not exist: " + value + " (a field YAML, or zoo:SEED:INDEX)";
}

sim::RobotConfig load_robot(const std::optional<std::filesystem::path>& file) {
  return file ? io::load_config<sim::RobotConfig>(*file) : sim::RobotConfig{};
}

sim::SimConfig load_sensors(const std::optional<std::filesystem::path>& file,
                            const std::string& lidar_preset_override) {
  sim::SimConfig config = file ? io::load_sim_config(*file) : sim::SimConfig{};
  if (!lidar_preset_override.empty()) {
    const Eigen::Vector3d xyz = config.lidar.mount_xyz, rpy = config.lidar.mount_rpy_deg;
    const double max_offset = config.lidar.max_mount_offset;
    config.lidar = sim::lidar_preset(lidar_preset_override);
    config.lidar.mount_xyz = xyz;
    config.lidar.mount_rpy_deg = rpy;
    config.lidar.max_mount_offset = max_offset;
  }
  return config;
}

sim::PathConfig load_path(const std::optional<std::filesystem::path>& file) {
  return file ? io::load_config<sim::PathConfig>(*file) : sim::PathConfig{};
}

core::Pose2 path_start(const std::vector<sim::PathPoint>& path) {
  if (path.size() < 2) return {};
  const Eigen::Vector2d d = path[1].p - path[0].p;
  return {path[0].p.x(), path[0].p.y(), std::atan2(d.y(), d.x())};
}

Eigen::Isometry3d mount_transform(const std::vector<double>& m) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(core::deg2rad(m[5]), Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(core::deg2rad(m[4]), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(core::deg2rad(m[3]), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(m[0], m[1], m[2]);
  return T;
}

}  // namespace rownav::app
