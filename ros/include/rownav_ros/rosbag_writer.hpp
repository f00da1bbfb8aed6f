#pragma once
/// @file rosbag_writer.hpp A rownav recording written as a ROS 1 bag (`.bag`, librosbag), the
/// counterpart of io::write_mcap_recording for ROS 1: the topics a robot's drivers publish.
/// Clouds on /points (sensor_msgs/PointCloud2, frame `lidar`), scans on /scan, the IMU on /imu
/// (frame `base_link`), the ground-truth poses on /odom (nav_msgs/Odometry odom -> base_link: a
/// simulator's perfect odometry), the LiDAR mount on /tf_static (base_link -> lidar) when the
/// recording's manifest gives it, and the manifest itself (YAML) on /rownav/manifest
/// (std_msgs/String), which read_rosbag_recording reads back. Built only with ROS (docs/bags.md).
#include <filesystem>

#include "rownav/io/recording.hpp"

namespace rownav::ros_bridge {

/// Topic of the recording's manifest in a bag rownav writes.
inline constexpr const char* kManifestTopic = "/rownav/manifest";

/// Writes `rec` to `file`, messages in stamp order. InputError when librosbag cannot write it.
void write_rosbag_recording(const io::Recording& rec, const std::filesystem::path& file);

/// Registers write_rosbag_recording for ".bag" (io::register_bag_writer).
void register_rosbag_writer();

}  // namespace rownav::ros_bridge
