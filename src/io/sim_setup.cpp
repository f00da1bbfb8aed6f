#include "rownav/io/sim_setup.hpp"

#include "rownav/io/input_error.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/sim/lidar_presets.hpp"

namespace rownav::io {

namespace {

std::string mark_of(const YAML::Node& n) {
  return std::to_string(n.Mark().line + 1) + ":" + std::to_string(n.Mark().column + 1);
}

}  // namespace

sim::SimConfig decode_sim_config(const YAML::Node& node, const std::string& file) {
  sim::SimConfig config;
  if (!node || node.IsNull()) return config;
  if (!node.IsMap()) throw InputError(file, mark_of(node), "expected a map of sensor settings");
  if (const YAML::Node lidar = node["lidar"]; lidar && lidar.IsMap() && lidar["preset"]) {
    const YAML::Node preset = lidar["preset"];
    try {
      config.lidar = sim::lidar_preset(preset.as<std::string>());
    } catch (const std::exception& e) {
      throw InputError(file, mark_of(preset), std::string("lidar.preset: ") + e.what());
    }
    decode_config(lidar, config.lidar, file, {"preset"}, false);
    YAML::Node rest = YAML::Clone(node);
    rest.remove("lidar");
    decode_config(rest, config, file, {}, false);
  } else {
    decode_config(node, config, file, {}, false);
  }
  try {
    config.validate();
  } catch (const std::invalid_argument& e) {
    detail::yaml_fail_validation(file, node, "", e.what());  // at the offending key's line:col
  }
  return config;
}

sim::SimConfig load_sim_config(const std::filesystem::path& file) {
  return decode_sim_config(load_yaml_file(file), file.string());
}

void RecordingSink::on_cloud(const core::PointCloud& cloud, const std::vector<sim::SurfaceClass>&) {
  if (keep()) writer_.write_cloud(cloud);
}

void RecordingSink::on_scan(const core::Scan2D& scan, const std::vector<sim::SurfaceClass>&) {
  if (keep()) writer_.write_scan(scan);
}

}  // namespace rownav::io
