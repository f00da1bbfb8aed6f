#include <CLI/CLI.hpp>
#include <iostream>

#include "rownav/core/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"rownav: map-free LiDAR row navigation for vineyards, orchards and row crops"};
  app.set_version_flag("--version", rownav::core::version());
  app.require_subcommand(0);
  CLI11_PARSE(app, argc, argv);
  std::cout << app.help();
  return 0;
}
