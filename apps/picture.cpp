#include "picture.hpp"

#include <algorithm>
#include <cmath>

#include "rownav/io/canvas.hpp"
#include "rownav/io/top_view.hpp"

namespace rownav::app {

namespace {

const io::Color kRobot = io::Color::hex("#d62728");
const io::Color kScan = io::Color::hex("#ff7f0e");
const io::Color kPath = io::Color::hex("#c2185b");

// Keeps pictures of big fields within ~2400 px across.
double fit_scale(const Eigen::AlignedBox2d& box) {
  const double extent = std::max(box.sizes().x(), box.sizes().y());
  return std::clamp(2000.0 / std::max(extent, 1.0), 4.0, 40.0);
}

Eigen::AlignedBox2d default_window(const sim::Field& field) {
  Eigen::AlignedBox2d b = field.row_bounds();
  const double h = field.headland_width;
  b.extend(b.min() - Eigen::Vector2d(h, h));
  b.extend(b.max() + Eigen::Vector2d(h, h));
  return b;
}

}  // namespace

Eigen::AlignedBox2d window_around(const Eigen::Vector2d& centre, double half_x, double half_y) {
  return {centre - Eigen::Vector2d(half_x, half_y), centre + Eigen::Vector2d(half_x, half_y)};
}

void write_picture(const std::filesystem::path& out, const sim::Field& field,
                   const PictureContent& content) {
  auto canvas = io::make_canvas(out);
  io::TopViewOptions options;
  options.title = content.title;
  options.window = content.window ? *content.window : default_window(field);
  options.pixels_per_metre =
      content.pixels_per_metre > 0 ? content.pixels_per_metre : fit_scale(*options.window);
  io::Style path_style;
  path_style.stroke = kPath;
  path_style.stroke_width_px = 2.0;
  if (!content.trajectory.empty()) options.extra_legend.emplace_back("driven path", path_style);
  if (content.robot_pose) options.extra_legend.emplace_back("robot", io::robot_legend_style(kRobot));
  if (content.scan) options.extra_legend.emplace_back("LiDAR scan", io::scan_legend_style(kScan));
  io::draw_field(*canvas, field, options);
  if (!content.trajectory.empty()) io::draw_path(*canvas, content.trajectory, path_style);
  if (content.cloud) {
    // Colour by height above the ground under the robot, not by world z (sloped fields).
    const Eigen::Isometry3d T_level_lidar =
        Eigen::Translation3d(0.0, 0.0, -content.ground_z) * content.T_world_lidar;
    io::draw_cloud(*canvas, *content.cloud, T_level_lidar, -0.1, 2.1);
  }
  if (content.scan) {
    const Eigen::Isometry3d& T = content.T_world_lidar;
    const core::Pose2 T_world_lidar(T.translation().x(), T.translation().y(),
                                    std::atan2(T.linear()(1, 0), T.linear()(0, 0)));
    io::draw_scan(*canvas, *content.scan, T_world_lidar, kScan);
  }
  if (content.robot_pose)
    io::draw_robot(*canvas, *content.robot_pose, content.robot.length, content.robot.width, kRobot);
  canvas->save(out);
}

}  // namespace rownav::app
