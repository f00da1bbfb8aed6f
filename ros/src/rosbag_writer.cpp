// A recording written as a ROS 1 bag through librosbag (rownav_ros/rosbag_writer.hpp).
#include "rownav_ros/rosbag_writer.hpp"

#include <rosbag/bag.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "rownav/io/bag_recording.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav/io/sim_setup.hpp"
#include "rownav_ros/conversions.hpp"

namespace rownav::ros_bridge {

namespace {

// The LiDAR mount of the manifest's sensors (a rownav recording), if it has one.
std::optional<Eigen::Isometry3d> lidar_mount(const io::Recording& rec) {
  if (!rec.manifest || !rec.manifest.IsMap() || !rec.manifest["sensors"]) return std::nullopt;
  try {
    return io::decode_sim_config(rec.manifest["sensors"], rec.dir.string()).lidar.T_base_lidar();
  } catch (const std::exception&) {
    return std::nullopt;  // a manifest from elsewhere: no mount to publish
  }
}

// A bag's record times start at ros::TIME_MIN (1 ns): a recording starting at 0 s keeps its
// header stamps (what the readers use), only the record time of those messages moves by 1 ns.
ros::Time bag_time(double stamp) {
  return std::max(ros::TIME_MIN, ros::Time(std::max(0.0, stamp)));
}

void write_header(rosbag::Bag& bag, const io::Recording& rec, double t0) {
  if (rec.manifest && !rec.manifest.IsNull()) {
    YAML::Emitter e;
    e << rec.manifest;
    std_msgs::String m;
    m.data = e.c_str();
    bag.write(kManifestTopic, bag_time(t0), m);
  }
  if (const auto mount = lidar_mount(rec)) {
    tf2_msgs::TFMessage tf;
    tf.transforms.push_back(to_transform_msg(std::max(0.0, t0), "base_link", "lidar", *mount));
    bag.write("/tf_static", bag_time(t0), tf);
  }
}

void write_entry(rosbag::Bag& bag, const io::Recording& rec, const io::BagEntry& e) {
  const ros::Time t = bag_time(e.stamp);
  switch (e.stream) {
    case io::BagStream::cloud: {
      core::PointCloud c = rec.cloud(e.index);
      c.frame_id = "lidar";
      bag.write("/points", t, to_cloud_msg(c));
      break;
    }
    case io::BagStream::scan:
      bag.write("/scan", t, to_scan_msg(rec.scans[e.index]));
      break;
    case io::BagStream::imu:
      bag.write("/imu", t, to_imu_msg(rec.imu[e.index], "base_link"));
      break;
    case io::BagStream::odom: {
      const auto& g = rec.ground_truth[e.index];
      bag.write("/odom", t, to_odom_msg({g.stamp, g.T_world_base, g.twist, "odom", "base_link"}));
      break;
    }
  }
}

}  // namespace

void write_rosbag_recording(const io::Recording& rec, const std::filesystem::path& file) {
  try {
    rosbag::Bag bag(file.string(), rosbag::bagmode::Write);
    const std::vector<io::BagEntry> entries = io::bag_entries(rec);
    write_header(bag, rec, entries.empty() ? 0.0 : entries.front().stamp);
    for (const io::BagEntry& e : entries) write_entry(bag, rec, e);
    bag.close();
  } catch (const rosbag::BagException& e) {
    throw io::InputError(file.string(), "", std::string("rosbag: ") + e.what());
  }
}

void register_rosbag_writer() {
  io::register_bag_writer(".bag", write_rosbag_recording);
}

}  // namespace rownav::ros_bridge
