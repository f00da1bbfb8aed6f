#pragma once
/// @file conversions.hpp ROS 1 messages <-> rownav core types (REP 103 units and axes on both
/// sides, so no axis swap happens here).
#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/Transform.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/time.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>

#include <Eigen/Geometry>
#include <string>

#include "rownav/core/point_cloud.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/core/scan2d.hpp"
#include "rownav/core/sensor_samples.hpp"
#include "rownav/core/twist.hpp"

namespace rownav::ros_bridge {

/// Wheel odometry as published by the robot base (nav_msgs/Odometry): the planar pose of the
/// child frame (base_link) in the odom frame and its body-frame velocity.
struct OdomSample {
  double stamp = 0.0;         ///< [s]
  core::Pose2 T_odom_base;    ///< planar part of pose.pose (yaw from the quaternion)
  core::Twist2 twist;         ///< twist.twist: linear.x, linear.y, angular.z (child frame)
  std::string frame_id;       ///< header.frame_id (odom)
  std::string child_frame_id; ///< child_frame_id (base_link)
};

/// [s] since the epoch.
double to_sec(const ros::Time& t);
/// [rad] yaw (rotation about z) of a quaternion; a zero quaternion gives 0.
double yaw_of(const geometry_msgs::Quaternion& q);
/// A tf2 transform as an isometry (the quaternion is normalised).
Eigen::Isometry3d to_isometry(const geometry_msgs::Transform& t);

/// PointCloud2 -> PointCloud. Needs float32 / float64 fields x, y, z; reads `intensity`, `ring`
/// and the per-point time (`time` or `t` or `timestamp`: integer fields are nanoseconds, float
/// fields seconds; values later than 1e6 s are absolute and made relative to the header stamp)
/// when present, and flags them in has_intensity / has_ring / has_time. Organised clouds are
/// read row by row (row_step). NaN points are kept (the pipeline drops them). Throws
/// std::invalid_argument on a malformed message (missing x/y/z, truncated data, field out of
/// the point, big-endian data).
core::PointCloud to_point_cloud(const sensor_msgs::PointCloud2& msg);
/// PointCloud -> PointCloud2 (x, y, z, intensity float32; ring uint16; time float32 [s]),
/// unorganised (height 1), dense when every point is finite. For tests and republishing.
sensor_msgs::PointCloud2 to_cloud_msg(const core::PointCloud& cloud);

/// LaserScan -> Scan2D (same conventions: bearings counter-clockwise, +inf = no return).
/// Intensities are copied only when there is one per range.
core::Scan2D to_scan(const sensor_msgs::LaserScan& msg);
/// Scan2D -> LaserScan (the inverse of to_scan; scan_time = ranges x time_increment).
sensor_msgs::LaserScan to_scan_msg(const core::Scan2D& scan);
/// Imu -> ImuSample (angular velocity, linear acceleration; orientation ignored).
core::ImuSample to_imu(const sensor_msgs::Imu& msg);
/// Odometry -> OdomSample.
OdomSample to_odom(const nav_msgs::Odometry& msg);
/// Twist2 -> geometry_msgs/Twist (linear.x = v, linear.y = vy, angular.z = omega).
geometry_msgs::Twist to_twist_msg(const core::Twist2& cmd);

/// [rad] rotation about z as a unit quaternion (the inverse of yaw_of).
geometry_msgs::Quaternion yaw_quaternion(double yaw);
/// OdomSample -> Odometry (the inverse of to_odom; covariances zero).
nav_msgs::Odometry to_odom_msg(const OdomSample& s);
/// ImuSample -> Imu in `frame_id`, without orientation (orientation_covariance[0] = -1, REP 145).
sensor_msgs::Imu to_imu_msg(const core::ImuSample& s, const std::string& frame_id);
/// `T_parent_child` at `stamp` [s] as a tf2 message (the inverse of to_isometry).
geometry_msgs::TransformStamped to_transform_msg(double stamp, const std::string& parent,
                                                 const std::string& child,
                                                 const Eigen::Isometry3d& T_parent_child);

}  // namespace rownav::ros_bridge
