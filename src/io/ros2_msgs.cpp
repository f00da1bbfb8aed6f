// ROS 2 LaserScan / Odometry / Imu in CDR (io/ros2_msgs.hpp).
#include "rownav/io/ros2_msgs.hpp"

#include <cmath>

namespace rownav::io {

namespace {

constexpr double kNanosecondsPerSecond = 1e9;
constexpr std::size_t kPoseCovariance = 36;  // geometry_msgs/PoseWithCovariance: double[36]
constexpr std::size_t kImuCovariance = 9;    // sensor_msgs/Imu: double[9] per quantity
constexpr std::size_t kQuaternionComponents = 4;  // geometry_msgs/Quaternion x, y, z, w

Eigen::Vector3d read_vector3(CdrReader& r) {
  const double x = r.f64(), y = r.f64(), z = r.f64();
  return {x, y, z};
}

void write_vector3(CdrWriter& w, const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) w.f64(v[i]);
}

void skip_doubles(CdrReader& r, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) r.f64();
}

void write_zeros(CdrWriter& w, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) w.f64(0.0);
}

std::vector<float> read_floats(CdrReader& r) {
  std::vector<float> v(r.sequence_length(sizeof(float)));
  for (auto& x : v) x = r.f32();
  return v;
}

void write_floats(CdrWriter& w, const std::vector<float>& v) {
  w.u32(static_cast<std::uint32_t>(v.size()));
  for (const float x : v) w.f32(x);
}

}  // namespace

Ros2Header read_header(CdrReader& r) {
  Ros2Header h;
  const std::int32_t sec = r.i32();
  const std::uint32_t nsec = r.u32();
  if (nsec >= kNanosecondsPerSecond)
    throw CdrError("header stamp nanosec " + std::to_string(nsec) + " is not below 1e9");
  h.stamp = static_cast<double>(sec) + static_cast<double>(nsec) / kNanosecondsPerSecond;
  h.frame_id = r.string();
  return h;
}

void write_header(CdrWriter& w, double stamp, const std::string& frame_id) {
  const double sec = std::floor(stamp);
  auto nsec = static_cast<std::int64_t>(std::llround((stamp - sec) * kNanosecondsPerSecond));
  auto s = static_cast<std::int64_t>(sec);
  if (nsec >= static_cast<std::int64_t>(kNanosecondsPerSecond)) ++s, nsec = 0;
  w.i32(static_cast<std::int32_t>(s));
  w.u32(static_cast<std::uint32_t>(nsec));
  w.string(frame_id);
}

core::Scan2D decode_laser_scan(std::span<const std::uint8_t> msg) {
  CdrReader r(msg);
  core::Scan2D s;
  const Ros2Header h = read_header(r);
  s.stamp = h.stamp;
  s.frame_id = h.frame_id;
  s.angle_min = r.f32();
  r.f32();  // angle_max: implied by angle_min, angle_increment and the number of ranges
  s.angle_increment = r.f32();
  s.time_increment = r.f32();
  r.f32();  // scan_time
  s.range_min = r.f32();
  s.range_max = r.f32();
  s.ranges = read_floats(r);
  s.intensities = read_floats(r);
  if (!s.intensities.empty() && s.intensities.size() != s.ranges.size())
    throw CdrError("LaserScan with " + std::to_string(s.intensities.size()) +
                   " intensities for " + std::to_string(s.ranges.size()) + " ranges");
  return s;
}

std::vector<std::uint8_t> encode_laser_scan(const core::Scan2D& s) {
  CdrWriter w;
  write_header(w, s.stamp, s.frame_id);
  const double n = s.ranges.empty() ? 0.0 : static_cast<double>(s.ranges.size() - 1);
  w.f32(static_cast<float>(s.angle_min));
  w.f32(static_cast<float>(s.angle_min + n * s.angle_increment));
  w.f32(static_cast<float>(s.angle_increment));
  w.f32(static_cast<float>(s.time_increment));
  w.f32(static_cast<float>(n * s.time_increment));
  w.f32(static_cast<float>(s.range_min));
  w.f32(static_cast<float>(s.range_max));
  write_floats(w, s.ranges);
  write_floats(w, s.intensities);
  return w.data();
}

localize::StampedPose decode_odometry(std::span<const std::uint8_t> msg) {
  CdrReader r(msg);
  localize::StampedPose s;
  s.stamp = read_header(r).stamp;
  r.string();  // child_frame_id: the base frame
  const Eigen::Vector3d p = read_vector3(r);
  const double qx = r.f64(), qy = r.f64(), qz = r.f64(), qw = r.f64();
  skip_doubles(r, kPoseCovariance);
  const Eigen::Vector3d v = read_vector3(r);
  const Eigen::Vector3d omega = read_vector3(r);
  skip_doubles(r, kPoseCovariance);
  // Yaw of the quaternion (Z-Y-X convention, as tf2::getYaw).
  const double yaw = std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz));
  s.T_odom_base = core::Pose2(p.x(), p.y(), yaw);
  s.twist = {v.x(), v.y(), omega.z()};
  return s;
}

std::vector<std::uint8_t> encode_odometry(const localize::StampedPose& s,
                                          const std::string& frame_id,
                                          const std::string& child_frame_id) {
  CdrWriter w;
  write_header(w, s.stamp, frame_id);
  w.string(child_frame_id);
  write_vector3(w, {s.T_odom_base.x, s.T_odom_base.y, 0.0});
  const double half = 0.5 * s.T_odom_base.theta;
  for (const double q : {0.0, 0.0, std::sin(half), std::cos(half)}) w.f64(q);
  write_zeros(w, kPoseCovariance);
  write_vector3(w, {s.twist.v, s.twist.vy, 0.0});
  write_vector3(w, {0.0, 0.0, s.twist.omega});
  write_zeros(w, kPoseCovariance);
  return w.data();
}

core::ImuSample decode_imu(std::span<const std::uint8_t> msg) {
  CdrReader r(msg);
  core::ImuSample s;
  s.stamp = read_header(r).stamp;
  skip_doubles(r, kQuaternionComponents);  // orientation quaternion x, y, z, w (not used)
  skip_doubles(r, kImuCovariance);
  s.angular_velocity = read_vector3(r);
  skip_doubles(r, kImuCovariance);
  s.linear_acceleration = read_vector3(r);
  skip_doubles(r, kImuCovariance);
  return s;
}

std::vector<std::uint8_t> encode_imu(const core::ImuSample& s, const std::string& frame_id) {
  CdrWriter w;
  write_header(w, s.stamp, frame_id);
  for (const double q : {0.0, 0.0, 0.0, 1.0}) w.f64(q);
  // orientation_covariance[0] = -1: "no orientation estimate" (sensor_msgs/Imu's convention).
  w.f64(-1.0);
  write_zeros(w, kImuCovariance - 1);
  write_vector3(w, s.angular_velocity);
  write_zeros(w, kImuCovariance);
  write_vector3(w, s.linear_acceleration);
  write_zeros(w, kImuCovariance);
  return w.data();
}

}  // namespace rownav::io
