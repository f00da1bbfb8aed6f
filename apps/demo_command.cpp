// `rownav demo`: the main job in one command: a narrow vineyard served end to end, closed loop.
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "rownav/core/version.hpp"
#include "rownav/io/input_error.hpp"
#include "run_mission.hpp"

namespace rownav::app {

void add_demo_command(CLI::App& app) {
  auto out = std::make_shared<std::filesystem::path>("out/demo");
  auto config_dir = std::make_shared<std::filesystem::path>("config");
  auto quiet = std::make_shared<bool>(false);
  CLI::App* c = app.add_subcommand(
      "demo",
      "The main job: a skid-steer robot with an OS1-16 serves every corridor of a "
      "10-row narrow vineyard by itself (closed loop on the simulated LiDAR); writes "
      "summary.json and report.html");
  c->add_option("--out", *out, "output directory (default out/demo)");
  c->add_option("--config-dir", *config_dir, "the repository's config/ directory (default config)");
  c->add_flag("--quiet", *quiet, "no progress bar");
  auto overwrite = std::make_shared<bool>(false);
  c->add_flag("--overwrite", *overwrite,
              "replace --out when it holds an earlier rownav output (never another folder)");
  c->callback([out, config_dir, quiet, overwrite] {
    const auto& d = *config_dir;
    RunArgs a;
    a.field = d / "fields/demo_vineyard.yaml";
    a.robot = d / "robots/skid_steer.yaml";
    a.sensor = d / "sensors/os1_16.yaml";
    a.mission = d / "missions/serve_all.yaml";
    a.detect_config = d / "detect/vineyard.yaml";
    a.nav_config = d / "navigate/vineyard.yaml";
    a.out = *out;
    a.quiet = *quiet;
    a.overwrite = *overwrite;
    for (const auto& f : {a.field, a.robot, *a.sensor, a.mission, *a.detect_config, *a.nav_config})
      if (!std::filesystem::exists(f))
        throw io::InputError(f.string(), "",
                             "not found (run from the repository or pass --config-dir)");
    std::cout << "rownav " << core::version()
              << " demo: skid-steer robot, OS1-16, serving every corridor of " << a.field.string()
              << "\n";
    if (!run_mission(a)) {
      std::cout.flush();
      std::exit(1);
    }
  });
}

}  // namespace rownav::app
