// ROS 1 bags read as recordings through librosbag (rownav_ros/rosbag_reader.hpp).
#include "rownav_ros/rosbag_reader.hpp"

#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/String.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <memory>
#include <numeric>

#include "rownav/io/input_error.hpp"
#include "rownav_ros/conversions.hpp"
#include "rownav_ros/rosbag_writer.hpp"

namespace rownav::ros_bridge {

namespace {

namespace fs = std::filesystem;

constexpr const char* kCloud = "sensor_msgs/PointCloud2";
constexpr const char* kScan = "sensor_msgs/LaserScan";
constexpr const char* kImu = "sensor_msgs/Imu";
constexpr const char* kOdom = "nav_msgs/Odometry";

/// The topic of a stream: the named one (checked to exist and to be of `type`), else the first
/// connection of that type, else empty.
std::string choose(rosbag::View& all, const std::string& named, const char* type,
                   const char* stream, const fs::path& file) {
  for (const rosbag::ConnectionInfo* c : all.getConnections()) {
    if (!named.empty() && c->topic != named) continue;
    if (named.empty() && c->datatype != type) continue;
    if (c->datatype != type)
      throw io::InputError(file.string(), "topic " + c->topic,
                           "is " + c->datatype + ", not " + type);
    return c->topic;
  }
  if (!named.empty())
    throw io::InputError(file.string(), "",
                         "--topics " + std::string(stream) + "=" + named + ": no such topic in the bag");
  return {};
}

/// The bag kept open for the replay: clouds decoded one at a time, in view order.
struct CloudSource {
  rosbag::Bag bag;
  std::unique_ptr<rosbag::View> view;
  rosbag::View::iterator it;
  std::size_t next = 0;  // view index `it` points at
  std::vector<std::size_t> order;  // view index of the i-th cloud by stamp

  core::PointCloud at(std::size_t i, const fs::path& file) {
    const std::size_t k = order.at(i);
    if (k < next || !view) view.reset(), next = 0;
    if (!view) view = std::make_unique<rosbag::View>(bag, rosbag::TopicQuery(topic)), it = view->begin();
    for (; next < k; ++next) ++it;
    try {
      return to_point_cloud(*it->instantiate<sensor_msgs::PointCloud2>());
    } catch (const std::exception& e) {
      throw io::InputError(file.string(), "topic " + topic + " cloud " + std::to_string(i), e.what());
    }
  }
  std::string topic;
};

/// The manifest a bag written by rownav carries (rosbag_writer.hpp), so that a replay keeps the
/// LiDAR mount; a bag from elsewhere has none.
YAML::Node read_manifest(rosbag::Bag& bag, const fs::path& file) {
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery(kManifestTopic))) {
    const auto s = m.instantiate<std_msgs::String>();
    if (!s) continue;
    try {
      return YAML::Load(s->data);
    } catch (const YAML::Exception& e) {
      throw io::InputError(file.string(), std::string("topic ") + kManifestTopic, e.what());
    }
  }
  return {};
}

template <class T>
void sort_by_stamp(std::vector<T>& v) {
  std::stable_sort(v.begin(), v.end(), [](const T& a, const T& b) { return a.stamp < b.stamp; });
}

}  // namespace

io::Recording read_rosbag_recording(const fs::path& file, const io::BagTopics& topics) {
  auto src = std::make_shared<CloudSource>();
  io::Recording rec;
  rec.dir = file;
  try {
    src->bag.open(file.string(), rosbag::bagmode::Read);
    rec.manifest = read_manifest(src->bag, file);
    rosbag::View all(src->bag);
    src->topic = choose(all, topics.cloud, kCloud, "cloud", file);
    const std::string scan = choose(all, topics.scan, kScan, "scan", file);
    const std::string imu = choose(all, topics.imu, kImu, "imu", file);
    const std::string odom = choose(all, topics.odom, kOdom, "odom", file);
    std::vector<std::string> wanted;
    for (const auto& t : {src->topic, scan, imu, odom})
      if (!t.empty()) wanted.push_back(t);
    std::size_t index = 0;
    for (const rosbag::MessageInstance& m : rosbag::View(src->bag, rosbag::TopicQuery(wanted))) {
      try {
        const std::string& t = m.getTopic();
        if (t == src->topic)
          rec.cloud_stamps.push_back(to_sec(m.instantiate<sensor_msgs::PointCloud2>()->header.stamp));
        else if (t == scan) rec.scans.push_back(to_scan(*m.instantiate<sensor_msgs::LaserScan>()));
        else if (t == imu) rec.imu.push_back(to_imu(*m.instantiate<sensor_msgs::Imu>()));
        else if (t == odom) {
          const OdomSample o = to_odom(*m.instantiate<nav_msgs::Odometry>());
          rec.odometry.push_back({o.stamp, o.T_odom_base, o.twist});
        }
      } catch (const std::exception& e) {
        throw io::InputError(file.string(), "topic " + m.getTopic() + " message " + std::to_string(index), e.what());
      }
      ++index;
    }
  } catch (const rosbag::BagException& e) {
    throw io::InputError(file.string(), "", std::string("rosbag: ") + e.what());
  }
  sort_by_stamp(rec.scans), sort_by_stamp(rec.imu), sort_by_stamp(rec.odometry);
  src->order.resize(rec.cloud_stamps.size());
  std::iota(src->order.begin(), src->order.end(), 0);
  std::stable_sort(src->order.begin(), src->order.end(), [&](std::size_t a, std::size_t b) {
    return rec.cloud_stamps[a] < rec.cloud_stamps[b];
  });
  std::sort(rec.cloud_stamps.begin(), rec.cloud_stamps.end());
  rec.cloud_files.assign(rec.cloud_stamps.size(), "");
  rec.cloud_source = [src, file](std::size_t i) {
    core::PointCloud c = src->at(i, file);
    c.drop_invalid();  // as the MCAP reader: NaN points are no returns
    return c;
  };
  return rec;
}

void register_rosbag_reader() { io::register_bag_reader(".bag", read_rosbag_recording); }

}  // namespace rownav::ros_bridge
