// ROS 2 CDR and the messages rownav reads from bags: layout, round trips, malformed input.
#include "rownav/io/cdr.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "rownav/io/ros2_cloud.hpp"
#include "rownav/io/ros2_msgs.hpp"

namespace rownav::io {
namespace {

TEST(Cdr, AlignsEachPrimitiveToItsSizeAfterTheEncapsulationHeader) {
  CdrWriter w;
  w.u8(7);
  w.f64(1.5);  // 7 bytes of padding: offset 8 after the header
  w.u16(0x0102);
  w.string("ab");  // uint32 length 3 at offset 20 (2 bytes padding), 'a' 'b' NUL
  const auto& d = w.data();
  ASSERT_EQ(d.size(), 4u + 8 + 8 + 2 + 2 + 4 + 3);
  EXPECT_EQ(d[1], 0x01);  // CDR_LE
  EXPECT_EQ(d[4], 7);
  EXPECT_EQ(d[4 + 16], 0x02);  // little-endian uint16
  EXPECT_EQ(d[4 + 20], 3);     // string length counts the NUL
  CdrReader r(d);
  EXPECT_EQ(r.u8(), 7);
  EXPECT_EQ(r.f64(), 1.5);
  EXPECT_EQ(r.u16(), 0x0102);
  EXPECT_EQ(r.string(), "ab");
  EXPECT_EQ(r.remaining(), 0u);
}

TEST(Cdr, ReadsBigEndian) {
  CdrWriter w(true);
  w.u32(0x01020304);
  w.f32(-2.25f);
  EXPECT_EQ(w.data()[1], 0x00);  // CDR_BE
  EXPECT_EQ(w.data()[4], 0x01);
  CdrReader r(w.data());
  EXPECT_TRUE(r.big_endian());
  EXPECT_EQ(r.u32(), 0x01020304u);
  EXPECT_EQ(r.f32(), -2.25f);
}

TEST(Cdr, TruncatedOrForeignMessagesAreErrors) {
  CdrWriter w;
  w.u32(100);  // a sequence of 100 floats, none there
  CdrReader r(w.data());
  EXPECT_THROW(r.sequence_length(sizeof(float)), CdrError);
  CdrReader s(w.data());
  s.u32();
  EXPECT_THROW(s.u8(), CdrError);
  const std::vector<std::uint8_t> xcdr2 = {0x00, 0x07, 0, 0, 1, 2, 3, 4};  // PL_CDR2_LE
  EXPECT_THROW(CdrReader{xcdr2}, CdrError);
  EXPECT_THROW(CdrReader(std::vector<std::uint8_t>{0, 1}), CdrError);
  CdrWriter bad;
  bad.u32(2);
  bad.u8('a'), bad.u8('b');  // no NUL
  CdrReader b(bad.data());
  EXPECT_THROW(b.string(), CdrError);
}

core::PointCloud sample_cloud() {
  core::PointCloud c;
  c.stamp = 1234.5678;
  c.frame_id = "os_lidar";
  c.has_intensity = c.has_ring = c.has_time = true;
  for (int i = 0; i < 6; ++i) {
    core::PointXYZIRT p;
    p.x = 1.0f + 0.5f * static_cast<float>(i), p.y = -0.25f * static_cast<float>(i), p.z = 0.125f;
    p.intensity = 10.0f * static_cast<float>(i);
    p.ring = static_cast<std::uint16_t>(i % 3);
    p.column = static_cast<std::uint16_t>(i % 3);
    p.time = 0.001f * static_cast<float>(i);
    c.points.push_back(p);
  }
  return c;
}

TEST(Ros2Cloud, RoundTripsWithEachTimeField) {
  const core::PointCloud c = sample_cloud();
  for (const auto time : {CloudTimeField::ouster_t, CloudTimeField::velodyne_time,
                          CloudTimeField::timestamp}) {
    const core::PointCloud d = decode_point_cloud2(encode_point_cloud2(c, time));
    EXPECT_NEAR(d.stamp, c.stamp, 1e-9);
    EXPECT_EQ(d.frame_id, "os_lidar");
    ASSERT_EQ(d.size(), c.size());
    EXPECT_TRUE(d.has_intensity && d.has_ring && d.has_time);
    for (std::size_t i = 0; i < c.size(); ++i) {
      EXPECT_EQ(d.points[i].x, c.points[i].x);
      EXPECT_EQ(d.points[i].y, c.points[i].y);
      EXPECT_EQ(d.points[i].z, c.points[i].z);
      EXPECT_EQ(d.points[i].intensity, c.points[i].intensity);
      EXPECT_EQ(d.points[i].ring, c.points[i].ring);
      EXPECT_EQ(d.points[i].column, c.points[i].column);
      EXPECT_NEAR(d.points[i].time, c.points[i].time, 1e-7) << static_cast<int>(time);
    }
  }
  const auto v = decode_point_cloud2(encode_point_cloud2(c, CloudTimeField::velodyne_time));
  EXPECT_EQ(v.points[5].time, c.points[5].time);  // float seconds: exact
  core::PointCloud bare = c;
  bare.has_intensity = bare.has_ring = bare.has_time = false;  // only x, y, z are written
  const auto b = encode_point_cloud2(bare);
  EXPECT_LT(b.size(), encode_point_cloud2(c).size());
  const core::PointCloud e = decode_point_cloud2(b);
  EXPECT_FALSE(e.has_intensity || e.has_ring || e.has_time);
  EXPECT_EQ(e.points[5].y, c.points[5].y);
  EXPECT_EQ(e.points[5].ring, 0);
}

TEST(Ros2Cloud, OrganisedCloudsGiveColumnsAndDropNaNPoints) {
  core::PointCloud c = sample_cloud();
  c.has_ring = false;  // no ring / column fields: the column is the organised cloud's column
  c.points[4].x = std::numeric_limits<float>::quiet_NaN();
  const core::PointCloud d = decode_point_cloud2(encode_point_cloud2(c, CloudTimeField::ouster_t, 2));
  ASSERT_EQ(d.size(), 5u);
  EXPECT_EQ(d.points[3].column, 0);  // row 1, column 0 (the 4th point)
  EXPECT_EQ(d.points[4].column, 2);  // row 1, column 2: column 1 was NaN
  EXPECT_EQ(d.points[4].x, c.points[5].x);
  EXPECT_THROW(encode_point_cloud2(c, CloudTimeField::ouster_t, 4), std::invalid_argument);
}

/// A PointCloud2 as another driver writes it: float64 x / y / z at odd offsets, a uint8 ring,
/// a 40-byte point, big-endian data in a little-endian message, two rows with row padding.
std::vector<std::uint8_t> foreign_cloud(std::uint32_t z_offset, std::uint32_t data_bytes) {
  CdrWriter w;
  write_header(w, 7.25, "velodyne");
  w.u32(2), w.u32(1);  // height 2, width 1
  w.u32(4);
  const std::pair<const char*, std::uint32_t> fields[] = {{"x", 1}, {"y", 9}, {"z", z_offset}};
  for (const auto& [name, off] : fields) w.string(name), w.u32(off), w.u8(8), w.u32(1);
  w.string("ring"), w.u32(30), w.u8(2), w.u32(1);
  w.boolean(true);
  w.u32(40), w.u32(48);  // point_step, row_step (8 bytes of padding a row)
  std::vector<std::uint8_t> d(data_bytes, 0);
  auto put_be = [&](std::size_t at, double v) {
    std::uint64_t u;
    std::memcpy(&u, &v, sizeof(u));
    for (int i = 0; i < 8; ++i) d[at + std::size_t(i)] = std::uint8_t(u >> (56 - 8 * i));
  };
  for (std::size_t row = 0; row < 2; ++row) {
    put_be(row * 48 + 1, 3.0 + double(row)), put_be(row * 48 + 9, -1.5), put_be(row * 48 + 17, 0.5);
    d[row * 48 + 30] = std::uint8_t(5 + row);
  }
  w.u32(data_bytes);
  w.bytes(d);
  w.boolean(true);
  return w.data();
}

TEST(Ros2Cloud, ReadsAnyLayoutTypeAndByteOrder) {
  const core::PointCloud c = decode_point_cloud2(foreign_cloud(17, 88));
  EXPECT_EQ(c.stamp, 7.25);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c.points[1].x, 4.0f);
  EXPECT_EQ(c.points[1].y, -1.5f);
  EXPECT_EQ(c.points[1].z, 0.5f);
  EXPECT_EQ(c.points[1].ring, 6);
  EXPECT_FALSE(c.has_time);
  EXPECT_FALSE(c.has_intensity);
}

TEST(Ros2Cloud, MalformedCloudsAreErrors) {
  EXPECT_THROW(decode_point_cloud2(foreign_cloud(36, 88)), CdrError);  // z outside the point
  EXPECT_THROW(decode_point_cloud2(foreign_cloud(17, 80)), CdrError);  // data too short
  auto msg = encode_point_cloud2(sample_cloud());
  msg.resize(msg.size() / 2);
  EXPECT_THROW(decode_point_cloud2(msg), CdrError);  // truncated message
}

TEST(Ros2Msgs, LaserScanOdometryAndImuRoundTrip) {
  core::Scan2D s;
  s.stamp = 3.5, s.frame_id = "laser", s.angle_min = -1.0, s.angle_increment = 0.25;
  s.time_increment = 1e-4, s.range_min = 0.1, s.range_max = 30.0;
  s.ranges = {1.0f, std::numeric_limits<float>::infinity(), 2.5f}, s.intensities = {1, 2, 3};
  const core::Scan2D t = decode_laser_scan(encode_laser_scan(s));
  EXPECT_EQ(t.stamp, 3.5);
  EXPECT_EQ(t.frame_id, "laser");
  EXPECT_EQ(t.angle_min, -1.0);
  EXPECT_EQ(t.angle_increment, 0.25);
  EXPECT_EQ(t.ranges, s.ranges);
  EXPECT_EQ(t.intensities, s.intensities);
  EXPECT_NEAR(t.range_max, 30.0, 1e-6);

  const localize::StampedPose o{10.125, core::Pose2(3.0, -2.0, 2.5), {0.8, 0.05, -0.3}};
  const localize::StampedPose p = decode_odometry(encode_odometry(o));
  EXPECT_EQ(p.stamp, 10.125);
  EXPECT_EQ(p.T_odom_base.x, 3.0);
  EXPECT_EQ(p.T_odom_base.y, -2.0);
  EXPECT_NEAR(p.T_odom_base.theta, 2.5, 1e-14);
  EXPECT_EQ(p.twist.v, 0.8);
  EXPECT_EQ(p.twist.vy, 0.05);
  EXPECT_EQ(p.twist.omega, -0.3);

  core::ImuSample i;
  i.stamp = 0.005, i.angular_velocity = {0.1, -0.2, 0.3}, i.linear_acceleration = {0.4, 0.5, 9.8};
  const core::ImuSample j = decode_imu(encode_imu(i));
  EXPECT_EQ(j.stamp, 0.005);
  EXPECT_EQ(j.angular_velocity, i.angular_velocity);
  EXPECT_EQ(j.linear_acceleration, i.linear_acceleration);
  auto bad = encode_imu(i);
  bad.pop_back();
  EXPECT_THROW(decode_imu(bad), CdrError);
}

}  // namespace
}  // namespace rownav::io
