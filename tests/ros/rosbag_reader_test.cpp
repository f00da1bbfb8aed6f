// ROS 1 bags (librosbag) read as recordings: a bag written here with rosbag::Bag, read back;
// and recordings written as ROS 1 bags (rosbag_writer), read back.
#include "rownav_ros/rosbag_reader.hpp"

#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Imu.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "common/cli_runner.hpp"
#include "rownav/io/bag_recording.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav/sim/ground_truth.hpp"
#include "rownav_ros/conversions.hpp"
#include "rownav_ros/rosbag_writer.hpp"

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

TEST(RosbagWriter, ARecordingWrittenAsABagReadsBackWithItsStreamsAndManifest) {
  test::TempDir dir("rosbag_writer");
  io::Recording rec;
  rec.manifest["sensors"]["lidar"]["mount_xyz"] = std::vector<double>{0.3, 0.0, 0.75};
  for (int k = 0; k < 10; ++k) rec.cloud_stamps.push_back(0.1 * k);  // from 0 s: ros::Time 0
  rec.cloud_files.assign(rec.cloud_stamps.size(), "");
  rec.cloud_source = [](std::size_t i) { return cloud_at(0.1 * double(i)); };
  for (int k = 0; k < 50; ++k) {
    core::ImuSample s;
    s.stamp = 0.02 * k, s.angular_velocity.z() = 0.01 * k, s.linear_acceleration.z() = 9.81;
    rec.imu.push_back(s);
    sim::GroundTruth g;
    g.stamp = 0.02 * k, g.T_world_base = core::Pose2(0.01 * k, 0.5, 0.02 * k), g.twist.v = 0.5;
    rec.ground_truth.push_back(g);
  }
  write_rosbag_recording(rec, dir / "rec.bag");
  const io::Recording back = read_rosbag_recording(dir / "rec.bag");
  ASSERT_EQ(back.cloud_count(), rec.cloud_count());
  for (std::size_t i = 0; i < rec.cloud_count(); ++i) {
    EXPECT_NEAR(back.cloud_stamps[i], rec.cloud_stamps[i], 1e-9);
    EXPECT_EQ(back.cloud(i).size(), 4u);  // the no-return point dropped on reading
  }
  ASSERT_EQ(back.imu.size(), 50u);
  EXPECT_NEAR(back.imu[7].angular_velocity.z(), 0.07, 1e-12);
  // The ground truth is the bag's odometry (a simulator's perfect odometry).
  ASSERT_EQ(back.odometry.size(), 50u);
  EXPECT_NEAR(back.odometry[20].T_odom_base.x, 0.2, 1e-12);
  EXPECT_NEAR(back.odometry[20].T_odom_base.theta, 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(back.odometry[20].twist.v, 0.5);
  // The manifest comes back (the LiDAR mount of a replay), and /tf_static holds the mount.
  ASSERT_TRUE(back.manifest.IsMap());
  EXPECT_DOUBLE_EQ(back.manifest["sensors"]["lidar"]["mount_xyz"][2].as<double>(), 0.75);
  rosbag::Bag bag((dir / "rec.bag").string(), rosbag::bagmode::Read);
  int tf = 0;
  for (const auto& m : rosbag::View(bag, rosbag::TopicQuery("/tf_static")))
    if (const auto t = m.instantiate<tf2_msgs::TFMessage>()) {
      ASSERT_EQ(t->transforms.size(), 1u);
      EXPECT_EQ(t->transforms[0].header.frame_id, "base_link");
      EXPECT_EQ(t->transforms[0].child_frame_id, "lidar");
      EXPECT_NEAR(t->transforms[0].transform.translation.z, 0.75, 1e-12);
      ++tf;
    }
  EXPECT_EQ(tf, 1);
}

TEST(RosbagWriter, RownavSimWritesABagThatTracksLikeItsMcap) {
  test::TempDir dir("rosbag_sim");
  std::ofstream(dir / "field.yaml")
      << "kind: vineyard\nname: tiny\nseed: 3\nvineyard:\n  rows: 3\n  row_length: 6.0\n";
  const test::Result sim = test::rownav(
      dir.path(), "sim --field field.yaml --out rec --bag rec.bag --mcap rec.mcap --quiet");
  ASSERT_EQ(sim.code, 0) << sim.err;
  EXPECT_NE(sim.out.find("ROS 1 bag: rec.bag"), std::string::npos) << sim.out;
  const std::string track = "track --detector hough_skew --tracker line_ekf --detect-config " +
                            std::string(ROWNAV_SOURCE_DIR) + "/config/detect/vineyard.yaml --in ";
  const test::Result b = test::rownav(dir.path(), track + "rec.bag --out b.csv");
  ASSERT_EQ(b.code, 0) << b.err;
  const test::Result m = test::rownav(dir.path(), track + "rec.mcap --out m.csv");
  ASSERT_EQ(m.code, 0) << m.err;
  // Same streams, same manifest: the two bags differ only in how stamps and per-point times are
  // stored (ROS 1 sec + nsec, float32 s). Measured: 315 of 315 statuses equal, lateral offsets
  // within 0.12 mm.
  std::stringstream bs(test::read_file(dir / "b.csv")), ms(test::read_file(dir / "m.csv"));
  int rows = 0, same = 0;
  for (std::string bl, ml; std::getline(bs, bl) && std::getline(ms, ml); ++rows) {
    const auto cell = [](const std::string& line, int k) {
      std::stringstream ls(line);
      std::string c;
      for (int i = 0; i <= k; ++i) std::getline(ls, c, ',');
      return c;
    };
    same += cell(bl, 1) == cell(ml, 1);
    const std::string lb = cell(bl, 3), lm = cell(ml, 3);
    if (rows > 0 && !lb.empty() && !lm.empty()) {
      EXPECT_NEAR(std::stod(lb), std::stod(lm), 1e-3);
    }
  }
  EXPECT_GT(rows, 100);
  EXPECT_GE(same, rows - 2);
  // A bag name the build cannot write is said before the drive, one line.
  const test::Result bad = test::rownav(dir.path(), "sim --field field.yaml --out rec2 --bag rec.db3 --quiet");
  EXPECT_EQ(bad.code, 2);
  EXPECT_EQ(bad.err.rfind("rownav: error: rec.db3: unknown bag format", 0), 0u) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "rec2"));
}

}  // namespace
}  // namespace rownav::ros_bridge
