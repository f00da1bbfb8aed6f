#pragma once
/// @file rosbag_reader.hpp ROS 1 bags (`.bag`, librosbag) read as rownav recordings, the
/// counterpart of io::read_mcap_recording for ROS 2: sensor_msgs/PointCloud2 (clouds, decoded
/// when the replay asks for them), LaserScan, Imu and nav_msgs/Odometry (the stack's external
/// odometry), each from one topic (the first connection of its type unless BagTopics names
/// one), every stream in header-stamp order. Built only with ROS (docs/ros.md).
#include <filesystem>

#include "rownav/io/bag_recording.hpp"

namespace rownav::ros_bridge {

/// InputError on a file librosbag cannot open or read, a malformed message, or a named topic
/// that is not in the bag / not of the right type.
io::Recording read_rosbag_recording(const std::filesystem::path& file,
                                    const io::BagTopics& topics = {});

/// Registers read_rosbag_recording for ".bag" (io::register_bag_reader).
void register_rosbag_reader();

}  // namespace rownav::ros_bridge
