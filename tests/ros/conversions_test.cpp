// ROS messages <-> rownav core types, on messages built by hand.
#include "rownav_ros/conversions.hpp"
#include "rownav_ros/ros_params.hpp"

#include <gtest/gtest.h>
#include <sensor_msgs/PointField.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace rb = rownav::ros_bridge;
using sensor_msgs::PointField;

namespace {

/// A cloud of `n` points laid out as x, y, z (float32), then `extra` fields appended by caller.
sensor_msgs::PointCloud2 xyz_cloud(std::uint32_t n, std::uint32_t point_step) {
  sensor_msgs::PointCloud2 m;
  m.header.stamp = ros::Time(100, 500000000);
  m.header.frame_id = "os_lidar";
  for (const char* name : {"x", "y", "z"}) {
    PointField f;
    f.name = name;
    f.offset = static_cast<std::uint32_t>(4 * m.fields.size());
    f.datatype = PointField::FLOAT32;
    f.count = 1;
    m.fields.push_back(f);
  }
  m.height = 1;
  m.width = n;
  m.point_step = point_step;
  m.row_step = n * point_step;
  m.data.assign(m.row_step, 0);
  return m;
}

template <class T>
void put(sensor_msgs::PointCloud2& m, std::uint32_t i, std::uint32_t offset, T v) {
  std::memcpy(m.data.data() + i * m.point_step + offset, &v, sizeof(T));
}

void add_field(sensor_msgs::PointCloud2& m, const char* name, std::uint32_t offset,
               std::uint8_t type) {
  PointField f;
  f.name = name;
  f.offset = offset;
  f.datatype = type;
  f.count = 1;
  m.fields.push_back(f);
}

}  // namespace

TEST(RosConversions, CloudXyzOnly) {
  auto m = xyz_cloud(2, 12);
  put(m, 0, 0, 1.5f), put(m, 0, 4, -2.0f), put(m, 0, 8, 0.25f);
  put(m, 1, 0, std::numeric_limits<float>::quiet_NaN());
  const auto c = rb::to_point_cloud(m);
  EXPECT_DOUBLE_EQ(c.stamp, 100.5);
  EXPECT_EQ(c.frame_id, "os_lidar");
  ASSERT_EQ(c.size(), 2u);  // NaN kept: the pipeline drops it
  EXPECT_FLOAT_EQ(c.points[0].x, 1.5f);
  EXPECT_FLOAT_EQ(c.points[0].y, -2.0f);
  EXPECT_FLOAT_EQ(c.points[0].z, 0.25f);
  EXPECT_TRUE(std::isnan(c.points[1].x));
  EXPECT_FALSE(c.has_intensity || c.has_ring || c.has_time);
}

TEST(RosConversions, CloudOusterFields) {
  // Ouster layout: intensity float32, t uint32 [ns], ring uint16, padding.
  auto m = xyz_cloud(1, 32);
  add_field(m, "intensity", 16, PointField::FLOAT32);
  add_field(m, "t", 20, PointField::UINT32);
  add_field(m, "ring", 24, PointField::UINT16);
  put(m, 0, 0, 3.0f), put(m, 0, 16, 42.0f), put(m, 0, 20, std::uint32_t{25000000});
  put(m, 0, 24, std::uint16_t{7});
  const auto c = rb::to_point_cloud(m);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_TRUE(c.has_intensity && c.has_ring && c.has_time);
  EXPECT_FLOAT_EQ(c.points[0].intensity, 42.0f);
  EXPECT_EQ(c.points[0].ring, 7);
  EXPECT_NEAR(c.points[0].time, 0.025, 1e-7);
}

TEST(RosConversions, CloudAbsoluteTimestampAndFloat64) {
  auto m = xyz_cloud(1, 24);
  m.fields[0].datatype = PointField::FLOAT64;  // x as float64 over bytes 0-7 -> move y, z
  m.fields[1].offset = 8;
  m.fields[2].offset = 12;
  add_field(m, "timestamp", 16, PointField::FLOAT64);
  m.header.stamp = ros::Time(1700000000, 0);
  put(m, 0, 0, 2.0), put(m, 0, 8, 1.0f), put(m, 0, 16, 1700000000.05);
  const auto c = rb::to_point_cloud(m);
  EXPECT_FLOAT_EQ(c.points[0].x, 2.0f);
  EXPECT_NEAR(c.points[0].time, 0.05, 1e-6);  // absolute -> relative to the header stamp
}

TEST(RosConversions, CloudOrganisedRowsUseRowStep) {
  auto m = xyz_cloud(2, 12);
  m.height = 2;
  m.row_step = 2 * 12 + 8;  // padded rows
  m.data.assign(m.row_step * 2, 0);
  std::memcpy(m.data.data() + m.row_step, &(const float&)4.0f, 4);
  const auto c = rb::to_point_cloud(m);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_FLOAT_EQ(c.points[2].x, 4.0f);
}

TEST(RosConversions, MalformedCloudsThrow) {
  auto no_z = xyz_cloud(1, 12);
  no_z.fields.pop_back();
  EXPECT_THROW(rb::to_point_cloud(no_z), std::invalid_argument);
  auto short_data = xyz_cloud(3, 12);
  short_data.data.resize(20);
  EXPECT_THROW(rb::to_point_cloud(short_data), std::invalid_argument);
  auto outside = xyz_cloud(1, 8);  // z at offset 8 does not fit in 8-byte points
  outside.row_step = 8;
  EXPECT_THROW(rb::to_point_cloud(outside), std::invalid_argument);
  auto empty = xyz_cloud(0, 12);
  EXPECT_TRUE(rb::to_point_cloud(empty).empty());
}

TEST(RosConversions, CloudRoundTrip) {
  rownav::core::PointCloud c;
  c.stamp = 12.25;
  c.frame_id = "velodyne";
  c.points.push_back({1.0f, 2.0f, 3.0f, 4.0f, 5, 0, 0.01f});
  c.points.push_back({std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f, 0.0f, 1, 0, 0.02f});
  const auto m = rb::to_cloud_msg(c);
  EXPECT_FALSE(m.is_dense);
  const auto back = rb::to_point_cloud(m);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_DOUBLE_EQ(back.stamp, 12.25);
  EXPECT_EQ(back.frame_id, "velodyne");
  EXPECT_FLOAT_EQ(back.points[0].z, 3.0f);
  EXPECT_FLOAT_EQ(back.points[0].intensity, 4.0f);
  EXPECT_EQ(back.points[0].ring, 5);
  EXPECT_FLOAT_EQ(back.points[1].time, 0.02f);
  EXPECT_TRUE(std::isnan(back.points[1].x));
}

TEST(RosConversions, LaserScan) {
  sensor_msgs::LaserScan m;
  m.header.stamp = ros::Time(5, 0);
  m.header.frame_id = "laser";
  m.angle_min = -1.0f;
  m.angle_increment = 0.5f;
  m.range_min = 0.1f;
  m.range_max = 20.0f;
  m.ranges = {1.0f, std::numeric_limits<float>::infinity(),
              std::numeric_limits<float>::quiet_NaN(), 30.0f};
  m.intensities = {1.0f};  // not one per range: dropped
  const auto s = rb::to_scan(m);
  EXPECT_DOUBLE_EQ(s.stamp, 5.0);
  EXPECT_DOUBLE_EQ(s.angle(2), 0.0);
  ASSERT_EQ(s.ranges.size(), 4u);
  EXPECT_TRUE(s.intensities.empty());
  EXPECT_TRUE(s.valid(0));
  EXPECT_FALSE(s.valid(1) || s.valid(2) || s.valid(3));
  EXPECT_EQ(s.to_points().size(), 1u);
}

TEST(RosConversions, LaserScanRoundTrip) {
  rownav::core::Scan2D s;
  s.stamp = 12.5, s.frame_id = "laser";
  s.angle_min = -2.0, s.angle_increment = 0.25, s.time_increment = 1e-4;
  s.range_min = 0.05, s.range_max = 30.0;
  s.ranges = {1.0f, std::numeric_limits<float>::infinity(), 2.5f};
  s.intensities = {10.f, 0.f, 7.f};
  const sensor_msgs::LaserScan m = rb::to_scan_msg(s);
  EXPECT_FLOAT_EQ(m.angle_max, -1.5f);  // angle_min + 2 increments
  EXPECT_FLOAT_EQ(m.scan_time, 3e-4f);
  const rownav::core::Scan2D back = rb::to_scan(m);
  EXPECT_DOUBLE_EQ(back.stamp, 12.5);
  EXPECT_EQ(back.frame_id, "laser");
  EXPECT_FLOAT_EQ(float(back.angle_min), -2.0f);
  EXPECT_FLOAT_EQ(float(back.angle_increment), 0.25f);
  EXPECT_EQ(back.ranges, s.ranges);
  EXPECT_EQ(back.intensities, s.intensities);
}

TEST(RosConversions, ImuOdometryTwist) {
  sensor_msgs::Imu imu;
  imu.header.stamp = ros::Time(2, 0);
  imu.angular_velocity.z = 0.3;
  imu.linear_acceleration.z = 9.81;
  const auto i = rb::to_imu(imu);
  EXPECT_DOUBLE_EQ(i.angular_velocity.z(), 0.3);
  EXPECT_DOUBLE_EQ(i.linear_acceleration.z(), 9.81);

  nav_msgs::Odometry o;
  o.header.stamp = ros::Time(3, 250000000);
  o.header.frame_id = "odom";
  o.child_frame_id = "base_link";
  o.pose.pose.position.x = 1.0;
  o.pose.pose.position.y = -2.0;
  o.pose.pose.orientation.z = std::sin(0.4);  // yaw 0.8
  o.pose.pose.orientation.w = std::cos(0.4);
  o.twist.twist.linear.x = 0.7;
  o.twist.twist.angular.z = -0.1;
  const auto s = rb::to_odom(o);
  EXPECT_DOUBLE_EQ(s.stamp, 3.25);
  EXPECT_DOUBLE_EQ(s.T_odom_base.y, -2.0);
  EXPECT_NEAR(s.T_odom_base.theta, 0.8, 1e-12);
  EXPECT_DOUBLE_EQ(s.twist.v, 0.7);
  EXPECT_DOUBLE_EQ(s.twist.omega, -0.1);
  EXPECT_EQ(s.child_frame_id, "base_link");

  const auto t = rb::to_twist_msg({0.5, 0.0, 0.2});
  EXPECT_DOUBLE_EQ(t.linear.x, 0.5);
  EXPECT_DOUBLE_EQ(t.angular.z, 0.2);
  EXPECT_DOUBLE_EQ(rb::yaw_of(geometry_msgs::Quaternion()), 0.0);  // zero quaternion
}

TEST(RosConversions, OdometryImuAndTransformMessagesRoundTrip) {
  rb::OdomSample o;
  o.stamp = 12.5;
  o.T_odom_base = rownav::core::Pose2(1.0, -2.0, 2.9);
  o.twist.v = 0.7, o.twist.vy = 0.01, o.twist.omega = -0.2;
  o.frame_id = "odom", o.child_frame_id = "base_link";
  const auto back = rb::to_odom(rb::to_odom_msg(o));
  EXPECT_DOUBLE_EQ(back.stamp, 12.5);
  EXPECT_DOUBLE_EQ(back.T_odom_base.x, 1.0);
  EXPECT_DOUBLE_EQ(back.T_odom_base.y, -2.0);
  EXPECT_NEAR(back.T_odom_base.theta, 2.9, 1e-12);
  EXPECT_DOUBLE_EQ(back.twist.v, 0.7);
  EXPECT_DOUBLE_EQ(back.twist.vy, 0.01);
  EXPECT_DOUBLE_EQ(back.twist.omega, -0.2);
  EXPECT_EQ(back.frame_id, "odom");
  EXPECT_EQ(back.child_frame_id, "base_link");
  EXPECT_NEAR(rb::yaw_of(rb::yaw_quaternion(-3.0)), -3.0, 1e-12);

  rownav::core::ImuSample i;
  i.stamp = 3.0;
  i.angular_velocity = {0.1, -0.2, 0.3};
  i.linear_acceleration = {0.5, 0.0, 9.81};
  const auto m = rb::to_imu_msg(i, "base_link");
  EXPECT_EQ(m.header.frame_id, "base_link");
  EXPECT_EQ(m.orientation_covariance[0], -1.0);  // no orientation
  const auto ib = rb::to_imu(m);
  EXPECT_DOUBLE_EQ(ib.stamp, 3.0);
  EXPECT_TRUE(ib.angular_velocity.isApprox(i.angular_velocity));
  EXPECT_TRUE(ib.linear_acceleration.isApprox(i.linear_acceleration));

  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 0.1, 1.0).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.3, -0.1, 0.75);
  const auto t = rb::to_transform_msg(4.0, "base_link", "lidar", T);
  EXPECT_EQ(t.header.frame_id, "base_link");
  EXPECT_EQ(t.child_frame_id, "lidar");
  EXPECT_DOUBLE_EQ(t.header.stamp.toSec(), 4.0);
  EXPECT_TRUE(rb::to_isometry(t.transform).isApprox(T, 1e-12));
}

TEST(RosParams, AListGivenAsTextOnTheCommandLineIsAList) {
  using rownav::ros_bridge::detail::numbers_from_text;
  // `rosrun rownav rownav_node _lidar_mount:="[0.3,0,0.8,0,0,0]"` stores the text.
  const auto v = numbers_from_text("[0.3,0,0.8,0,0,0]");
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(*v, (std::vector<double>{0.3, 0, 0.8, 0, 0, 0}));
  EXPECT_EQ(*numbers_from_text("1.5, -2e-1"), (std::vector<double>{1.5, -0.2}));
  EXPECT_FALSE(numbers_from_text("[0.3, x, 1]").has_value());
  EXPECT_FALSE(numbers_from_text("0.3m").has_value());
}
