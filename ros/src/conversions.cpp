// ROS 1 messages <-> rownav core types.
#include "rownav_ros/conversions.hpp"

#include <sensor_msgs/PointField.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string_view>

namespace rownav::ros_bridge {

namespace {

using sensor_msgs::PointField;

/// A field of the point layout: byte offset and datatype.
struct FieldReader {
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;
};

std::size_t datatype_size(std::uint8_t t) {
  switch (t) {
    case PointField::INT8:
    case PointField::UINT8: return 1;
    case PointField::INT16:
    case PointField::UINT16: return 2;
    case PointField::INT32:
    case PointField::UINT32:
    case PointField::FLOAT32: return 4;
    case PointField::FLOAT64: return 8;
    default: return 0;
  }
}

bool is_float(std::uint8_t t) { return t == PointField::FLOAT32 || t == PointField::FLOAT64; }

template <class T>
double load(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return static_cast<double>(v);
}

double read(const std::uint8_t* point, const FieldReader& f) {
  const std::uint8_t* p = point + f.offset;
  switch (f.datatype) {
    case PointField::INT8: return load<std::int8_t>(p);
    case PointField::UINT8: return load<std::uint8_t>(p);
    case PointField::INT16: return load<std::int16_t>(p);
    case PointField::UINT16: return load<std::uint16_t>(p);
    case PointField::INT32: return load<std::int32_t>(p);
    case PointField::UINT32: return load<std::uint32_t>(p);
    case PointField::FLOAT32: return load<float>(p);
    default: return load<double>(p);
  }
}

/// The first field named one of `names`, checked against the point size.
std::optional<FieldReader> find_field(const sensor_msgs::PointCloud2& msg,
                                      std::initializer_list<std::string_view> names) {
  for (const auto name : names)
    for (const auto& f : msg.fields) {
      if (f.name != name) continue;
      const std::size_t size = datatype_size(f.datatype);
      if (size == 0)
        throw std::invalid_argument("PointCloud2: field '" + f.name + "' has unknown datatype " +
                                    std::to_string(f.datatype));
      if (f.offset + size > msg.point_step)
        throw std::invalid_argument("PointCloud2: field '" + f.name + "' lies outside point_step");
      return FieldReader{f.offset, f.datatype};
    }
  return std::nullopt;
}

FieldReader require_field(const sensor_msgs::PointCloud2& msg, std::string_view name) {
  const auto f = find_field(msg, {name});
  if (!f || !is_float(f->datatype))
    throw std::invalid_argument("PointCloud2: needs a float32 / float64 field '" +
                                std::string(name) + "'");
  return *f;
}

void check_layout(const sensor_msgs::PointCloud2& msg) {
  if (msg.is_bigendian != (std::endian::native == std::endian::big))
    throw std::invalid_argument("PointCloud2: byte order differs from this machine's");
  const std::size_t row_bytes = std::size_t{msg.width} * msg.point_step;
  if (msg.point_step == 0 && msg.width * msg.height > 0)
    throw std::invalid_argument("PointCloud2: point_step is 0");
  if (msg.row_step < row_bytes)
    throw std::invalid_argument("PointCloud2: row_step smaller than width * point_step");
  const std::size_t need =
      msg.height == 0 ? 0 : std::size_t{msg.row_step} * (msg.height - 1) + row_bytes;
  if (msg.data.size() < need)
    throw std::invalid_argument("PointCloud2: data holds " + std::to_string(msg.data.size()) +
                                " bytes, the layout needs " + std::to_string(need));
}

}  // namespace

double to_sec(const ros::Time& t) { return static_cast<double>(t.sec) + 1e-9 * t.nsec; }

double yaw_of(const geometry_msgs::Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

Eigen::Isometry3d to_isometry(const geometry_msgs::Transform& t) {
  Eigen::Quaterniond q(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z);
  if (q.norm() < 1e-12) q = Eigen::Quaterniond::Identity();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(t.translation.x, t.translation.y, t.translation.z);
  return T;
}

core::PointCloud to_point_cloud(const sensor_msgs::PointCloud2& msg) {
  check_layout(msg);
  const FieldReader fx = require_field(msg, "x"), fy = require_field(msg, "y"),
                    fz = require_field(msg, "z");
  const auto fi = find_field(msg, {"intensity"});
  const auto fr = find_field(msg, {"ring"});
  const auto ft = find_field(msg, {"time", "t", "timestamp"});
  core::PointCloud cloud;
  cloud.stamp = to_sec(msg.header.stamp);
  cloud.frame_id = msg.header.frame_id;
  cloud.has_intensity = fi.has_value();
  cloud.has_ring = fr.has_value();
  cloud.has_time = ft.has_value();
  cloud.points.reserve(std::size_t{msg.width} * msg.height);
  for (std::uint32_t row = 0; row < msg.height; ++row) {
    const std::uint8_t* base = msg.data.data() + std::size_t{row} * msg.row_step;
    for (std::uint32_t col = 0; col < msg.width; ++col) {
      const std::uint8_t* p = base + std::size_t{col} * msg.point_step;
      core::PointXYZIRT q;
      q.x = static_cast<float>(read(p, fx));
      q.y = static_cast<float>(read(p, fy));
      q.z = static_cast<float>(read(p, fz));
      if (fi) q.intensity = static_cast<float>(read(p, *fi));
      if (fr) q.ring = static_cast<std::uint16_t>(read(p, *fr));
      if (ft) {
        double t = read(p, *ft);
        if (!is_float(ft->datatype)) t *= 1e-9;  // integer time fields are nanoseconds
        if (t > 1e6) t -= cloud.stamp;           // absolute stamps (e.g. Hesai `timestamp`)
        q.time = static_cast<float>(t);
      }
      cloud.points.push_back(q);
    }
  }
  return cloud;
}

sensor_msgs::PointCloud2 to_cloud_msg(const core::PointCloud& cloud) {
  sensor_msgs::PointCloud2 msg;
  msg.header.stamp.fromSec(cloud.stamp);
  msg.header.frame_id = cloud.frame_id;
  auto add = [&msg](const char* name, std::uint32_t offset, std::uint8_t type) {
    PointField f;
    f.name = name;
    f.offset = offset;
    f.datatype = type;
    f.count = 1;
    msg.fields.push_back(f);
  };
  add("x", 0, PointField::FLOAT32);
  add("y", 4, PointField::FLOAT32);
  add("z", 8, PointField::FLOAT32);
  add("intensity", 12, PointField::FLOAT32);
  add("ring", 16, PointField::UINT16);
  add("time", 20, PointField::FLOAT32);
  msg.point_step = 24;
  msg.height = 1;
  msg.width = static_cast<std::uint32_t>(cloud.points.size());
  msg.row_step = msg.point_step * msg.width;
  msg.is_bigendian = std::endian::native == std::endian::big;
  msg.is_dense = true;
  msg.data.resize(msg.row_step);
  std::uint8_t* out = msg.data.data();
  for (const auto& p : cloud.points) {
    std::memcpy(out + 0, &p.x, 4);
    std::memcpy(out + 4, &p.y, 4);
    std::memcpy(out + 8, &p.z, 4);
    std::memcpy(out + 12, &p.intensity, 4);
    std::memcpy(out + 16, &p.ring, 2);
    std::memcpy(out + 20, &p.time, 4);
    msg.is_dense = msg.is_dense && p.finite();
    out += msg.point_step;
  }
  return msg;
}

core::Scan2D to_scan(const sensor_msgs::LaserScan& msg) {
  core::Scan2D s;
  s.stamp = to_sec(msg.header.stamp);
  s.frame_id = msg.header.frame_id;
  s.angle_min = msg.angle_min;
  s.angle_increment = msg.angle_increment;
  s.time_increment = msg.time_increment;
  s.range_min = msg.range_min;
  s.range_max = msg.range_max;
  s.ranges = msg.ranges;
  if (msg.intensities.size() == msg.ranges.size()) s.intensities = msg.intensities;
  return s;
}

sensor_msgs::LaserScan to_scan_msg(const core::Scan2D& scan) {
  sensor_msgs::LaserScan msg;
  msg.header.stamp.fromSec(scan.stamp);
  msg.header.frame_id = scan.frame_id;
  msg.angle_min = static_cast<float>(scan.angle_min);
  msg.angle_increment = static_cast<float>(scan.angle_increment);
  msg.angle_max = static_cast<float>(
      scan.angle_min +
      scan.angle_increment * static_cast<double>(scan.ranges.empty() ? 0 : scan.ranges.size() - 1));
  msg.time_increment = static_cast<float>(scan.time_increment);
  msg.scan_time = static_cast<float>(scan.time_increment * static_cast<double>(scan.ranges.size()));
  msg.range_min = static_cast<float>(scan.range_min);
  msg.range_max = static_cast<float>(scan.range_max);
  msg.ranges = scan.ranges;
  msg.intensities = scan.intensities;
  return msg;
}

core::ImuSample to_imu(const sensor_msgs::Imu& msg) {
  core::ImuSample s;
  s.stamp = to_sec(msg.header.stamp);
  s.angular_velocity = {msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z};
  s.linear_acceleration = {msg.linear_acceleration.x, msg.linear_acceleration.y,
                           msg.linear_acceleration.z};
  return s;
}

OdomSample to_odom(const nav_msgs::Odometry& msg) {
  OdomSample s;
  s.stamp = to_sec(msg.header.stamp);
  const auto& p = msg.pose.pose;
  s.T_odom_base = core::Pose2(p.position.x, p.position.y, yaw_of(p.orientation));
  s.twist.v = msg.twist.twist.linear.x;
  s.twist.vy = msg.twist.twist.linear.y;
  s.twist.omega = msg.twist.twist.angular.z;
  s.frame_id = msg.header.frame_id;
  s.child_frame_id = msg.child_frame_id;
  return s;
}

geometry_msgs::Twist to_twist_msg(const core::Twist2& cmd) {
  geometry_msgs::Twist t;
  t.linear.x = cmd.v;
  t.linear.y = cmd.vy;
  t.angular.z = cmd.omega;
  return t;
}

geometry_msgs::Quaternion yaw_quaternion(double yaw) {
  geometry_msgs::Quaternion q;
  q.z = std::sin(yaw / 2.0);
  q.w = std::cos(yaw / 2.0);
  return q;
}

nav_msgs::Odometry to_odom_msg(const OdomSample& s) {
  nav_msgs::Odometry o;
  o.header.stamp.fromSec(s.stamp);
  o.header.frame_id = s.frame_id;
  o.child_frame_id = s.child_frame_id;
  o.pose.pose.position.x = s.T_odom_base.x;
  o.pose.pose.position.y = s.T_odom_base.y;
  o.pose.pose.orientation = yaw_quaternion(s.T_odom_base.theta);
  o.twist.twist.linear.x = s.twist.v;
  o.twist.twist.linear.y = s.twist.vy;
  o.twist.twist.angular.z = s.twist.omega;
  return o;
}

sensor_msgs::Imu to_imu_msg(const core::ImuSample& s, const std::string& frame_id) {
  sensor_msgs::Imu m;
  m.header.stamp.fromSec(s.stamp);
  m.header.frame_id = frame_id;
  m.orientation_covariance[0] = -1.0;  // no orientation (REP 145)
  m.angular_velocity.x = s.angular_velocity.x();
  m.angular_velocity.y = s.angular_velocity.y();
  m.angular_velocity.z = s.angular_velocity.z();
  m.linear_acceleration.x = s.linear_acceleration.x();
  m.linear_acceleration.y = s.linear_acceleration.y();
  m.linear_acceleration.z = s.linear_acceleration.z();
  return m;
}

geometry_msgs::TransformStamped to_transform_msg(double stamp, const std::string& parent,
                                                 const std::string& child,
                                                 const Eigen::Isometry3d& T_parent_child) {
  geometry_msgs::TransformStamped t;
  t.header.stamp.fromSec(stamp);
  t.header.frame_id = parent;
  t.child_frame_id = child;
  const Eigen::Vector3d& p = T_parent_child.translation();
  t.transform.translation.x = p.x(), t.transform.translation.y = p.y();
  t.transform.translation.z = p.z();
  const Eigen::Quaterniond q(T_parent_child.linear());
  t.transform.rotation.x = q.x(), t.transform.rotation.y = q.y();
  t.transform.rotation.z = q.z(), t.transform.rotation.w = q.w();
  return t;
}

}  // namespace rownav::ros_bridge
