#include <filesystem>
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "drive.hpp"
#include "picture.hpp"
#include "rownav/core/version.hpp"
#include "rownav/io/bag_recording.hpp"
#include "rownav/io/field_builder.hpp"
#include "rownav/io/recording.hpp"
#include "rownav/io/safe_output.hpp"
#include "rownav/io/sim_setup.hpp"
#include "rownav/io/yaml_config.hpp"
#include "setup.hpp"

namespace rownav::app {

namespace {

struct SimArgs {
  std::filesystem::path field, out, mcap, bag;
  std::optional<std::filesystem::path> robot, sensors, path;
  std::string lidar;
  int lidar_every = 1;
  double max_time = 3600.0;
  std::optional<std::uint64_t> seed;
  bool overwrite = false, quiet = false;
};

YAML::Node manifest(const Setup& s, const SimArgs& a) {
  YAML::Node m;
  m["generator"] = std::string("rownav ") + core::version() + " sim";
  m["field"] = io::encode_config(s.field_config);
  m["robot"] = io::encode_config(s.robot);
  m["sensors"] = io::encode_config(s.sensors);
  m["path"] = io::encode_config(s.path);
  m["lidar_every"] = a.lidar_every;
  return m;
}

// The scripted path, with build_path's "corridors[0]: reason" placed at that key of the path
// file (or naming the default path when there is no --path).
std::vector<sim::PathPoint> scripted_path(const sim::FieldTruth& truth, const Setup& s,
                                          const SimArgs& a) {
  try {
    return sim::build_path(truth, s.path, s.robot);
  } catch (const std::invalid_argument& e) {
    if (!a.path) throw std::invalid_argument(std::string("default path (no --path): ") + e.what());
    io::detail::yaml_fail_validation(a.path->string(), io::load_yaml_file(*a.path), "", e.what());
  }
}

void run_sim(const SimArgs& a) {
  if (!a.bag.empty()) io::check_bag_writable(a.bag);  // said before the drive
  Setup s;
  s.field = io::load_field(a.field, &s.field_config);
  s.robot = load_robot(a.robot);
  s.sensors = load_sensors(a.sensors, a.lidar);
  if (a.seed) s.sensors.seed = *a.seed;
  s.path = load_path(a.path);
  const sim::FieldTruth truth(s.field);
  const auto path = scripted_path(truth, s, a);
  sim::Simulator simulator(s.field, s.robot, s.sensors, path_start(path));
  sim::PathFollower driver(path);
  io::RecordingWriter writer(a.out, manifest(s, a), a.overwrite);
  writer.write_field(s.field);
  io::RecordingSink sink(writer, a.lidar_every);
  const DriveSummary d = run_scripted_drive(simulator, driver, sink, a.max_time, !a.quiet);
  // The MCAP is claimed before the drive's recording is moved into place: a refused name is
  // said before the work is kept (io/safe_output.hpp).
  std::optional<io::OutputFile> mcap, bag;
  if (!a.mcap.empty()) mcap.emplace(a.mcap, a.overwrite);
  if (!a.bag.empty()) bag.emplace(a.bag, a.overwrite);
  writer.commit();
  if (mcap || bag) {
    const io::Recording rec = io::read_recording(a.out);  // once for both bags
    if (mcap) {
      io::write_mcap_recording(rec, mcap->staging());
      mcap->commit();
      std::cout << "ROS 2 bag: " << a.mcap.string() << "\n";
    }
    if (bag) {
      io::write_bag_recording(rec, bag->staging(), a.bag);
      bag->commit();
      std::cout << (io::is_mcap_file(a.bag) ? "ROS 2 bag: " : "ROS 1 bag: ") << a.bag.string()
                << "\n";
    }
  }

  PictureContent pic;
  pic.trajectory = d.trajectory;
  pic.robot = s.robot;
  pic.title = "rownav sim: " + a.field.filename().string();
  write_picture(a.out / "top_view.png", s.field, pic);
  std::cout << "simulated " << d.sim_time << " s in " << d.wall_time << " s wall ("
            << d.lidar_frames << " LiDAR frames, " << sink.frames_written() << " recorded), "
            << (d.completed ? "path completed" : "path NOT completed (max time)") << ", in-lane "
            << "RMS offset " << d.lane_rms_lateral << " m, plants crushed " << d.plants_crushed
            << "\nrecording: " << a.out.string() << "  picture: " << (a.out / "top_view.png").string()
            << "\n";
}

}  // namespace

void add_sim_command(CLI::App& app) {
  auto args = std::make_shared<SimArgs>();
  CLI::App* c = app.add_subcommand(
      "sim", "Drive a scripted path through a simulated field and write a recording directory "
             "(PCD frames, CSV odometry / IMU / GNSS / ground truth, YAML manifest) plus a "
             "top-view picture");
  c->add_option("--field", args->field, "field YAML (config/fields/) or zoo:SEED:INDEX")->required()->check(check_field_arg);
  c->add_option("--robot", args->robot, "robot YAML (config/robots/); default skid-steer")->check(CLI::ExistingFile);
  c->add_option("--sensors", args->sensors, "sensors YAML (config/sensors/); default OS1-16")->check(CLI::ExistingFile);
  c->add_option("--lidar", args->lidar, "LiDAR preset overriding the sensors file (os1_16, os1_64, vlp16, sick_tim571, sick_lms111, lms_1081)");
  c->add_option("--path", args->path, "scripted path YAML (config/paths/); default corridors 0 and 1")->check(CLI::ExistingFile);
  c->add_option("--out", args->out, "recording directory to create")->required();
  c->add_option("--mcap", args->mcap,
                "also write the recording as a ROS 2 bag (MCAP, zstd): /points, /imu, and the "
                "true poses as /odom (docs/bags.md)");
  c->add_option("--bag", args->bag,
                "also write the recording as a bag, by extension: FILE.mcap (ROS 2) or FILE.bag "
                "(ROS 1, when rownav is built with ROS): /points, /scan, /imu, the true poses as "
                "/odom, /tf_static and the manifest on /rownav/manifest (docs/bags.md)");
  c->add_option("--lidar-every", args->lidar_every, "record one LiDAR frame in N")->check(CLI::PositiveNumber);
  c->add_option("--max-time", args->max_time, "[s] stop the drive after this simulated time")->check(CLI::PositiveNumber);
  c->add_option("--seed", args->seed, "seed of every noise source (overrides the sensors file)");
  c->add_flag("--overwrite", args->overwrite, "replace an existing output directory");
  c->add_flag("--quiet", args->quiet, "no progress bar");
  c->callback([args] { run_sim(*args); });
}

}  // namespace rownav::app
