#include "rownav/io/mission_io.hpp"

#include "rownav/io/yaml_config.hpp"

namespace rownav::io {

navigate::MissionPlan load_mission(const std::filesystem::path& file) {
  return load_config<navigate::MissionPlan>(file);
}

}  // namespace rownav::io
