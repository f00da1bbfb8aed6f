#include <CLI/CLI.hpp>
#include <algorithm>
#include <exception>
#include <iostream>
#include <string>

#include "commands.hpp"
#include "rownav/core/version.hpp"
#ifdef ROWNAV_WITH_ROSBAG
#include "rownav_ros/rosbag_reader.hpp"  // ROS 1 .bag files (built with ROS: ros/CMakeLists.txt)
#include "rownav_ros/rosbag_writer.hpp"
#endif

int main(int argc, char** argv) {
  CLI::App app{
      "rownav: map-free LiDAR row navigation for vineyards, orchards and row crops.\n"
      "Frames: x forward, y left, z up (REP 103); lengths in metres, angles in degrees on the "
      "command line and in configs."};
  app.set_version_flag("--version", rownav::core::version());
  app.require_subcommand(1);
#ifdef ROWNAV_WITH_ROSBAG
  rownav::ros_bridge::register_rosbag_reader();
  rownav::ros_bridge::register_rosbag_writer();
#endif
  rownav::app::add_sim_command(app);
  rownav::app::add_render_command(app);
  rownav::app::add_demo_command(app);
  rownav::app::add_config_command(app);
  rownav::app::add_detect_command(app);
  rownav::app::add_run_command(app);
  rownav::app::add_bench_command(app);
  rownav::app::add_track_command(app);
  rownav::app::add_zoo_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // Bad command line (missing option, nonexistent file, ...): the same one-line form.
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    std::cerr << "rownav: error: " << what << " (see --help)\n";
    return 2;
  } catch (const std::exception& e) {
    // One line: the file, the position and the reason (io::InputError) or the failing check.
    std::cerr << "rownav: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
