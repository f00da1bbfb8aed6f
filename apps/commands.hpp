#pragma once
/// @file commands.hpp The `rownav` subcommands; each file registers one.
#include <CLI/CLI.hpp>

namespace rownav::app {

void add_sim_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_demo_command(CLI::App& app);
void add_config_command(CLI::App& app);
void add_detect_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_track_command(CLI::App& app);
void add_zoo_command(CLI::App& app);

}  // namespace rownav::app
