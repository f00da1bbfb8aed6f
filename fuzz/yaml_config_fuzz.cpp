// Every YAML config kind through its strict loader. The first byte picks the kind (one corpus
// for all: the kinds share yaml-cpp and io::decode_config, and a mutation that moves a seed to
// another kind is a free "wrong file for this option" test); the rest is the file.
#include <array>
#include <functional>

#include "fuzz_common.hpp"
#include "rownav/io/controller_registry.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/io/localize_setup.hpp"
#include "rownav/io/mission_io.hpp"
#include "rownav/io/sim_setup.hpp"
#include "rownav/io/tracker_registry.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/navigate/nav_stack_config.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/robot.hpp"
#include "rownav/sim/scripted_path.hpp"

namespace {

namespace io = rownav::io;
using Path = std::filesystem::path;

/// A registry name chosen by `b`, so every detector / tracker / controller gets its turn.
std::string pick(const std::vector<std::string>& names, std::uint8_t b) {
  return names[b % names.size()];
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::uint8_t kind = data[0];
  const std::uint8_t sub = static_cast<std::uint8_t>(kind / 10);
  static const std::array<std::function<void(const Path&)>, 10> kLoaders = {
      [](const Path& f) { (void)io::load_config<rownav::sim::FieldConfig>(f); },
      [](const Path& f) { (void)io::load_config<rownav::sim::RobotConfig>(f); },
      [](const Path& f) { (void)io::load_sim_config(f); },
      [](const Path& f) { (void)io::load_config<rownav::sim::PathConfig>(f); },
      [](const Path& f) { (void)io::load_config<rownav::navigate::NavStackConfig>(f); },
      [](const Path& f) { (void)io::load_mission(f); },
      [](const Path& f) { (void)io::load_localizer_config(f); },
      [sub](const Path& f) { (void)io::make_pipeline(pick(io::detector_names(), sub), f); },
      [sub](const Path& f) { (void)io::make_tracker(pick(io::tracker_names(), sub), f); },
      [sub](const Path& f) { (void)io::make_controller(pick(io::controller_names(), sub), f); },
  };
  const auto file = rownav::fuzz::input_file("yaml", data + 1, size - 1);
  rownav::fuzz::expect_clean(file.string(), [&] { kLoaders[kind % kLoaders.size()](file); });
  return 0;
}
