#pragma once
/// @file ros2_msgs.hpp ROS 2 messages in CDR (io/cdr.hpp) to and from rownav's samples:
/// sensor_msgs/msg/LaserScan <-> core::Scan2D, nav_msgs/msg/Odometry <-> localize::StampedPose
/// (x, y, yaw of the pose; linear x / y and angular z of the twist), sensor_msgs/msg/Imu <->
/// core::ImuSample (angular velocity, linear acceleration; the orientation is not used).
/// PointCloud2 is in io/ros2_cloud.hpp. Decoders throw CdrError on a malformed message.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rownav/core/scan2d.hpp"
#include "rownav/core/sensor_samples.hpp"
#include "rownav/io/cdr.hpp"
#include "rownav/localize/pose_history.hpp"

namespace rownav::io {

inline constexpr const char* kRos2PointCloud2 = "sensor_msgs/msg/PointCloud2";
inline constexpr const char* kRos2LaserScan = "sensor_msgs/msg/LaserScan";
inline constexpr const char* kRos2Odometry = "nav_msgs/msg/Odometry";
inline constexpr const char* kRos2Imu = "sensor_msgs/msg/Imu";

/// std_msgs/Header: stamp [s] (sec + nanosec / 1e9) and frame_id.
struct Ros2Header {
  double stamp = 0.0;
  std::string frame_id;
};
Ros2Header read_header(CdrReader& r);
/// Writes `stamp` rounded to the nearest nanosecond.
void write_header(CdrWriter& w, double stamp, const std::string& frame_id);

core::Scan2D decode_laser_scan(std::span<const std::uint8_t> msg);
std::vector<std::uint8_t> encode_laser_scan(const core::Scan2D& scan);

/// T_odom_base from the pose (yaw of the quaternion), twist in the child (base) frame.
localize::StampedPose decode_odometry(std::span<const std::uint8_t> msg);
std::vector<std::uint8_t> encode_odometry(const localize::StampedPose& s,
                                          const std::string& frame_id = "odom",
                                          const std::string& child_frame_id = "base_link");

core::ImuSample decode_imu(std::span<const std::uint8_t> msg);
std::vector<std::uint8_t> encode_imu(const core::ImuSample& s, const std::string& frame_id = "imu");

}  // namespace rownav::io
