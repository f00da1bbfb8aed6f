// ROS 1 bags (librosbag) read as recordings: a bag written here with rosbag::Bag, read back.
#include "rownav_ros/rosbag_reader.hpp"

#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/Imu.h>
#include <std_msgs/String.h>

#include <cmath>
#include <fstream>

#include "common/cli_runner.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav_ros/conversions.hpp"

namespace rownav::ros_bridge {
namespace {

namespace fs = std::filesystem;

core::PointCloud cloud_at(double stamp) {
  core::PointCloud c;
  c.stamp = stamp;
  c.has_intensity = c.has_ring = c.has_time = true;
  for (int i = 0; i < 5; ++i) {
    core::PointXYZIRT p;
    p.x = float(stamp) + float(i), p.y = -0.5f, p.z = 0.25f, p.ring = std::uint16_t(i), p.time = 0.01f * float(i);
    c.points.push_back(p);
  }
  c.points[2].x = std::nanf("");  // no return
  return c;
}

/// Clouds at 0.1 s, IMU at 0.02 s, odometry at 0.05 s, a String topic, for 1 s; the clouds are
/// written with bag times out of their header order for one pair.
void write_bag(const fs::path& file) {
  rosbag::Bag bag(file.string(), rosbag::bagmode::Write);
  for (int k = 0; k <= 50; ++k) {
    const double t = 100.0 + 0.02 * k;
    sensor_msgs::Imu imu;
    imu.header.stamp = ros::Time(t);
    imu.linear_acceleration.z = 9.81, imu.angular_velocity.z = 0.01 * k;
    bag.write("/imu", ros::Time(t), imu);
    if (k % 5 == 0) {
      const double tc = k == 10 ? t + 0.2 + 0.02 : k == 20 ? t - 0.2 + 0.02 : t;  // swapped
      bag.write("/points", ros::Time(t + 0.01), to_cloud_msg(cloud_at(tc)));
    }
    if (k % 2 == 0) {
      nav_msgs::Odometry o;
      o.header.stamp = ros::Time(t);
      o.pose.pose.position.x = 0.5 * k * 0.02;
      o.pose.pose.orientation.z = std::sin(0.05), o.pose.pose.orientation.w = std::cos(0.05);
      o.twist.twist.linear.x = 0.5;
      bag.write("/odom", ros::Time(t), o);
    }
    std_msgs::String s;
    s.data = "noise";
    bag.write("/chatter", ros::Time(t), s);
  }
  bag.close();
}

TEST(RosbagReader, ReadsCloudsImuAndOdometryInStampOrder) {
  test::TempDir dir("rosbag");
  write_bag(dir / "run.bag");
  register_rosbag_reader();  // as rownav's main() does
  const io::Recording rec = io::read_bag_recording(dir / "run.bag");  // through the registry
  ASSERT_EQ(rec.cloud_count(), 11u);
  ASSERT_EQ(rec.imu.size(), 51u);
  ASSERT_EQ(rec.odometry.size(), 26u);
  EXPECT_TRUE(std::is_sorted(rec.cloud_stamps.begin(), rec.cloud_stamps.end()));
  for (std::size_t i = 0; i < rec.cloud_count(); ++i) {
    const core::PointCloud c = rec.cloud(i);
    EXPECT_NEAR(c.stamp, rec.cloud_stamps[i], 1e-9);
    ASSERT_EQ(c.size(), 4u);  // the NaN point dropped
    EXPECT_NEAR(c.points[0].x, float(c.stamp), 1e-4);
    EXPECT_EQ(c.points[3].ring, 4);
    EXPECT_NEAR(c.points[3].time, 0.04f, 1e-7);
  }
  EXPECT_NEAR(rec.imu[7].angular_velocity.z(), 0.07, 1e-12);
  EXPECT_NEAR(rec.odometry[3].T_odom_base.theta, 0.1, 1e-12);
  EXPECT_NEAR(rec.odometry[3].T_odom_base.x, 0.06, 1e-12);
  EXPECT_EQ(rec.odometry[3].twist.v, 0.5);
}

TEST(RosbagReader, BadBagsAndTopicsAreInputErrors) {
  test::TempDir dir("rosbag");
  write_bag(dir / "run.bag");
  io::BagTopics t;
  t.cloud = "/velodyne_points";
  EXPECT_THROW(read_rosbag_recording(dir / "run.bag", t), io::InputError);
  t.cloud = "/chatter";
  EXPECT_THROW(read_rosbag_recording(dir / "run.bag", t), io::InputError);
  std::ofstream(dir / "junk.bag") << "not a bag\n";
  EXPECT_THROW(read_rosbag_recording(dir / "junk.bag"), io::InputError);
  const std::string bytes = test::read_file(dir / "run.bag");
  std::ofstream(dir / "cut.bag", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  try {
    const io::Recording rec = read_rosbag_recording(dir / "cut.bag");
    for (std::size_t i = 0; i < rec.cloud_count(); ++i) (void)rec.cloud(i);
    ADD_FAILURE() << "a bag cut in half read without an error";
  } catch (const io::InputError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

TEST(RosbagReader, RownavDetectReadsABag) {
  test::TempDir dir("rosbag");
  write_bag(dir / "run.bag");
  const test::Result r = test::rownav(dir.path(), "detect --detector hough_skew --in run.bag --out rows.json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("hough_skew: 11 frame(s)"), std::string::npos) << r.out;
  const test::Result t = test::rownav(dir.path(), "track --detector hough_skew --tracker line_ekf "
                                                  "--in run.bag --lidar-mount 0,0,0,0,0,0 --out t.csv");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_EQ(t.out.rfind("odometry: nav_msgs/Odometry of the bag\n", 0), 0u) << t.out;
  EXPECT_NE(t.out.find(": 11 frame(s)"), std::string::npos) << t.out;
}

}  // namespace
}  // namespace rownav::ros_bridge
