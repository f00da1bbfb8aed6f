#pragma once
/// @file picture.hpp The top-view picture the commands write (field, truth, path, one LiDAR frame).
#include <Eigen/Geometry>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rownav/core/point_cloud.hpp"
#include "rownav/core/scan2d.hpp"
#include "rownav/sim/field.hpp"
#include "rownav/sim/robot.hpp"

namespace rownav::app {

/// What to draw over the field.
struct PictureContent {
  std::optional<core::PointCloud> cloud;  ///< in the LiDAR frame
  std::optional<core::Scan2D> scan;       ///< in the LiDAR frame
  Eigen::Isometry3d T_world_lidar = Eigen::Isometry3d::Identity();
  double ground_z = 0.0;  ///< [m] ground height under the robot (colour scale of the cloud)
  std::optional<core::Pose2> robot_pose;  ///< T_world_base
  sim::RobotConfig robot;
  std::vector<Eigen::Vector2d> trajectory;  ///< driven path (world)
  std::optional<Eigen::AlignedBox2d> window;
  double pixels_per_metre = 0.0;  ///< 0: chosen from the window size
  std::string title;
};

/// Writes a PNG or SVG (by extension) top view.
void write_picture(const std::filesystem::path& out, const sim::Field& field,
                   const PictureContent& content);

/// A window of +-half_size metres around a point.
Eigen::AlignedBox2d window_around(const Eigen::Vector2d& centre, double half_x, double half_y);

}  // namespace rownav::app
