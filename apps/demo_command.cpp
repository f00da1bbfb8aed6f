#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "drive.hpp"
#include "picture.hpp"
#include "rownav/core/version.hpp"
#include "rownav/io/field_builder.hpp"
#include "rownav/io/recording.hpp"
#include "rownav/io/sim_setup.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/lidar_presets.hpp"
#include "setup.hpp"

namespace rownav::app {

namespace {

// The demo field: a narrow vineyard at medium canopy with a few missing vines and some weeds.
sim::FieldConfig demo_field() {
  sim::FieldConfig f;
  f.kind = sim::FieldKind::vineyard;
  f.name = "demo_narrow_vineyard";
  f.vineyard.rows = 6;
  f.vineyard.row_length = 30.0;
  f.vineyard.row_spacing = 1.8;
  f.vineyard.stage = sim::GrowthStage::medium;
  f.vineyard.missing_plants_percent = 3.0;
  f.vineyard.weeds = sim::WeedLevel::some;
  f.seed = 7;
  return f;
}

void run_demo(const std::filesystem::path& out, bool quiet) {
  const sim::FieldConfig field_config = demo_field();
  std::cout << "rownav " << core::version() << " demo: building a " << field_config.vineyard.rows
            << "-row narrow vineyard, OS1-16, skid-steer robot, scripted drive through 2 "
               "corridors\n";
  const sim::Field field = io::build_field(field_config, ".");
  const sim::RobotConfig robot;
  sim::SimConfig sensors;
  sim::PathConfig path_config;
  path_config.corridors = {1, 2};
  const sim::FieldTruth truth(field);
  const auto path = sim::build_path(truth, path_config, robot);
  sim::Simulator simulator(field, robot, sensors, path_start(path));
  sim::PathFollower driver(path);

  YAML::Node manifest;
  manifest["generator"] = std::string("rownav ") + core::version() + " demo";
  manifest["field"] = io::encode_config(field_config);
  manifest["robot"] = io::encode_config(robot);
  manifest["sensors"] = io::encode_config(sensors);
  manifest["path"] = io::encode_config(path_config);
  const std::filesystem::path rec_dir = out / "recording";
  std::filesystem::create_directories(out);
  io::RecordingWriter writer(rec_dir, manifest, /*overwrite=*/true);
  writer.write_field(field);
  io::RecordingSink sink(writer, /*lidar_every=*/5);
  const DriveSummary d = run_scripted_drive(simulator, driver, sink, 600.0, !quiet);
  writer.commit();

  PictureContent pic;
  pic.trajectory = d.trajectory;
  pic.robot = robot;
  pic.title = "rownav demo: scripted drive, ground truth";
  write_picture(out / "top_view.png", field, pic);
  write_picture(out / "top_view.svg", field, pic);
  std::cout << "simulated " << d.sim_time << " s in " << d.wall_time << " s wall, "
            << d.lidar_frames << " OS1-16 sweeps (" << sink.frames_written()
            << " recorded), path " << (d.completed ? "completed" : "NOT completed")
            << ", in-lane RMS offset " << d.lane_rms_lateral << " m (max "
            << d.lane_max_lateral << " m), plants crushed " << d.plants_crushed << "\n"
            << "wrote " << rec_dir.string() << "/ and " << (out / "top_view.png").string() << "\n";
  if (!d.completed) throw std::runtime_error("demo drive did not complete its path");
}

}  // namespace

void add_demo_command(CLI::App& app) {
  auto out = std::make_shared<std::filesystem::path>("out/demo");
  auto quiet = std::make_shared<bool>(false);
  CLI::App* c = app.add_subcommand(
      "demo", "The main job: simulate a narrow vineyard, drive it, write a recording and a "
              "top-view picture (until the navigation stack lands, the drive is scripted)");
  c->add_option("--out", *out, "output directory (default out/demo)");
  c->add_flag("--quiet", *quiet, "no progress bar");
  c->callback([out, quiet] { run_demo(*out, *quiet); });
}

}  // namespace rownav::app
