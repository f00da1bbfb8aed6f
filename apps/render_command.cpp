#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "picture.hpp"
#include "rownav/core/angle.hpp"
#include "rownav/io/canvas.hpp"
#include "rownav/io/field_builder.hpp"
#include "rownav/io/recording.hpp"
#include "rownav/io/safe_output.hpp"
#include "rownav/io/sim_setup.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/ray_caster.hpp"
#include "rownav/sim/simulator.hpp"
#include "setup.hpp"

namespace rownav::app {

namespace {

struct RenderArgs {
  std::filesystem::path field, out;
  std::optional<std::filesystem::path> recording, robot, sensors;
  std::string lidar;
  std::optional<int> frame;
  std::vector<double> pose;  // x, y, yaw_deg
  int corridor = 0;
  double at = 0.33;  // fraction of the corridor length
  double scale = 0.0;
  bool whole = false;
  bool overwrite = false;
};

// Pose in the middle of a corridor, at a fraction of its length, facing along it.
core::Pose2 corridor_pose(const sim::Field& field, int corridor, double at) {
  const sim::FieldTruth truth(field);
  const auto& blocks = truth.blocks();
  if (blocks.empty() || corridor < 0 || corridor >= truth.corridor_count(blocks.front()))
    throw std::invalid_argument("--corridor " + std::to_string(corridor) + " does not exist");
  const auto& c = truth.corridor_centre(blocks.front(), corridor);
  const std::size_t i = std::min(c.size() - 2, static_cast<std::size_t>(at * (c.size() - 1)));
  const Eigen::Vector2d d = c[i + 1] - c[i];
  return {c[i].x(), c[i].y(), std::atan2(d.y(), d.x())};
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// The field's area: the rows' bounds grown by the headland (as sim::build_path), else the mesh's
// (an imported terrain without rows).
Eigen::AlignedBox2d field_area(const sim::Field& field) {
  Eigen::AlignedBox2d area = field.row_bounds();
  if (area.isEmpty()) {
    const Eigen::AlignedBox3f b = field.mesh.bounds();
    if (b.isEmpty()) return area;
    return {b.min().head<2>().cast<double>(), b.max().head<2>().cast<double>()};
  }
  const Eigen::Vector2d grow = Eigen::Vector2d::Constant(field.headland_width);
  return {area.min() - grow, area.max() + grow};
}

// --pose of a live scan, checked before the simulator sees it (issue 13: a huge x rendered an
// empty picture without a word, a NaN ended in "set_view: empty view").
core::Pose2 live_pose(const RenderArgs& a, const sim::Field& field) {
  if (a.pose.size() != 3) return corridor_pose(field, a.corridor, a.at);
  const double x = a.pose[0], y = a.pose[1], yaw_deg = a.pose[2];
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(yaw_deg))
    throw std::invalid_argument("--pose: x, y and yaw must be finite numbers");
  if (std::abs(yaw_deg) > 360.0)
    throw std::invalid_argument("--pose: yaw " + number(yaw_deg) + " deg is outside -360..360");
  const Eigen::AlignedBox2d area = field_area(field);
  if (!area.isEmpty() && !area.contains(Eigen::Vector2d(x, y)))
    throw std::invalid_argument("--pose: (" + number(x) + ", " + number(y) +
                                ") m is off the field (x " + number(area.min().x()) + ".." +
                                number(area.max().x()) + ", y " + number(area.min().y()) + ".." +
                                number(area.max().y()) + " m)");
  return {x, y, core::deg2rad(yaw_deg)};
}

void render_live(const RenderArgs& a, const sim::Field& field, PictureContent& pic) {
  const core::Pose2 pose = live_pose(a, field);
  const sim::SimConfig sensors = load_sensors(a.sensors, a.lidar);
  sim::Simulator simulator(field, pic.robot, sensors, pose);
  const Eigen::Isometry3d T_world_base = simulator.pose3d(pose);
  const sim::PoseAt pose_at = [&](double) { return T_world_base; };
  sim::Lidar lidar(sensors.lidar, sensors.seed);
  if (sensors.lidar.kind == sim::LidarKind::spinning)
    pic.cloud = lidar.sweep(simulator.world(), pose_at, 0.0);
  else
    pic.scan = lidar.scan(simulator.world(), pose_at, 0.0);
  pic.T_world_lidar = T_world_base * sensors.lidar.T_base_lidar();
  pic.ground_z = T_world_base.translation().z();
  pic.robot_pose = pose;
}

void render_recorded(const RenderArgs& a, PictureContent& pic) {
  const io::Recording rec = io::read_recording(*a.recording);
  const std::size_t n = rec.cloud_count() ? rec.cloud_count() : rec.scans.size();
  if (n == 0)
    throw std::invalid_argument(a.recording->string() + ": recording has no LiDAR frames");
  const std::size_t i = a.frame ? static_cast<std::size_t>(*a.frame) : n / 2;
  if (i >= n)
    throw std::invalid_argument("--frame " + std::to_string(i) + " out of range (0.." +
                                std::to_string(n - 1) + ")");
  const double stamp = rec.cloud_count() ? rec.cloud_stamps[i] : rec.scans[i].stamp;
  const sim::GroundTruth* g = nullptr;
  for (const auto& t : rec.ground_truth)
    if (!g || std::abs(t.stamp - stamp) < std::abs(g->stamp - stamp)) g = &t;
  if (!g) throw std::invalid_argument(a.recording->string() + ": recording has no ground truth");
  Eigen::Isometry3d T_world_base = Eigen::Isometry3d::Identity();
  T_world_base.linear() = (Eigen::AngleAxisd(g->T_world_base.theta, Eigen::Vector3d::UnitZ()) *
                           Eigen::AngleAxisd(g->pitch, Eigen::Vector3d::UnitY()) *
                           Eigen::AngleAxisd(g->roll, Eigen::Vector3d::UnitX()))
                              .toRotationMatrix();
  T_world_base.translation() = Eigen::Vector3d(g->T_world_base.x, g->T_world_base.y, g->z);
  const sim::SimConfig sensors =
      io::decode_sim_config(rec.manifest["sensors"], a.recording->string() + "/manifest.yaml");
  pic.T_world_lidar = T_world_base * sensors.lidar.T_base_lidar();
  pic.ground_z = g->z;
  if (rec.cloud_count())
    pic.cloud = rec.cloud(i);
  else
    pic.scan = rec.scans[i];
  pic.robot_pose = g->T_world_base;
  for (const auto& t : rec.ground_truth) pic.trajectory.push_back(t.T_world_base.translation());
}

void run_render(const RenderArgs& a) {
  io::picture_format(a.out);  // an unknown extension names the user's file, before the work
  io::OutputFile out(a.out, a.overwrite);  // refused names are said before the work
  sim::FieldConfig field_config;
  const sim::Field field = io::load_field(a.field, &field_config);
  PictureContent pic;
  pic.robot = load_robot(a.robot);
  pic.pixels_per_metre = a.scale;
  if (a.recording)
    render_recorded(a, pic);
  else
    render_live(a, field, pic);
  if (!a.whole && pic.robot_pose)
    pic.window = window_around(pic.robot_pose->translation(), 14.0, 9.0);
  pic.title =
      a.field.filename().string() + (a.recording ? "  (recorded frame)" : "  (one LiDAR frame)");
  write_picture(out.staging(), field, pic);
  out.commit();
  std::cout << "wrote " << a.out.string() << "\n";
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto a = std::make_shared<RenderArgs>();
  CLI::App* c = app.add_subcommand(
      "render",
      "Draw a top view (PNG or SVG) of a field with its ground truth (rows, corridor "
      "centres, posts, plants) and one LiDAR frame overlaid, coloured by height");
  c->add_option("--field", a->field, "field YAML or zoo:SEED:INDEX")
      ->required()
      ->check(check_field_arg);
  c->add_option("--out", a->out, "picture to write (.png, .svg or .pdf)")->required();
  c->add_flag("--overwrite", a->overwrite, "replace an existing --out file");
  c->add_option("--recording", a->recording,
                "take the frame from this recording (rownav sim --out)")
      ->check(CLI::ExistingDirectory);
  c->add_option("--frame", a->frame, "frame index in the recording (default: the middle one)");
  c->add_option("--pose", a->pose, "x,y,yaw_deg of the robot for a live scan (world frame)")
      ->delimiter(',')
      ->expected(3);
  c->add_option("--corridor", a->corridor, "corridor for a live scan when no --pose (default 0)");
  c->add_option("--at", a->at, "position along that corridor, 0..1 (default 0.33)")
      ->check(CLI::Range(0.0, 1.0));
  c->add_option("--sensors", a->sensors, "sensors YAML for a live scan")->check(CLI::ExistingFile);
  c->add_option("--lidar", a->lidar, "LiDAR preset for a live scan (default os1_16)");
  c->add_option("--robot", a->robot, "robot YAML (footprint, LiDAR mount)")
      ->check(CLI::ExistingFile);
  c->add_option("--scale", a->scale, "pixels per metre (default: fit)");
  c->add_flag("--whole", a->whole, "draw the whole field, not a window around the robot");
  c->callback([a] { run_render(*a); });
}

}  // namespace rownav::app
