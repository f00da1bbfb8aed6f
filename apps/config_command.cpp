#include <iostream>

#include "commands.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/navigate/nav_stack_config.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/lidar_presets.hpp"
#include "rownav/sim/robot.hpp"
#include "rownav/sim/scripted_path.hpp"
#include "rownav/sim/simulator.hpp"

namespace rownav::app {

namespace {

void dump(const std::string& what, const std::string& file) {
  YAML::Node node;
  if (what == "field") {
    node = io::encode_config(sim::FieldConfig{});
  } else if (what == "robot") {
    node = io::encode_config(sim::RobotConfig{});
  } else if (what == "sensors") {
    node = io::encode_config(sim::SimConfig{});
  } else if (what == "path") {
    node = io::encode_config(sim::PathConfig{});
  } else if (what == "navigate" || what == "stack") {
    node = io::encode_config(navigate::NavStackConfig{});
  } else if (what.rfind("lidar:", 0) == 0) {
    node = io::encode_config(sim::lidar_preset(what.substr(6)));
  } else {
    throw std::invalid_argument("config --dump: unknown kind '" + what +
                                "' (field, robot, sensors, path, navigate | stack, lidar:<preset>)");
  }
  if (!file.empty()) {
    io::save_yaml(file, node);
    return;
  }
  YAML::Emitter e;
  e << node;
  std::cout << e.c_str() << "\n";
}

}  // namespace

void add_config_command(CLI::App& app) {
  auto what = std::make_shared<std::string>();
  auto file = std::make_shared<std::string>();
  CLI::App* c = app.add_subcommand(
      "config", "Print the default configuration of a component as YAML (every key a config file "
                "may set, with its default value)");
  c->add_option("--dump", *what, "field | robot | sensors | path | navigate (= stack) | lidar:<preset>")
      ->required();
  c->add_option("--out", *file, "write to this file instead of stdout");
  c->callback([what, file] { dump(*what, *file); });
}

}  // namespace rownav::app
