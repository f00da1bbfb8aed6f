#pragma once
/// @file bag_recording.hpp ROS 2 bags (MCAP, CDR messages) as rownav recordings, and back.
///
/// Reading: sensor_msgs/msg/PointCloud2 -> Recording clouds (read from the bag on demand),
/// sensor_msgs/msg/LaserScan -> scans, sensor_msgs/msg/Imu -> imu, nav_msgs/msg/Odometry ->
/// Recording::odometry (fed to NavStack::on_odometry: an external odometry), each from one topic
/// (the first channel of its type unless BagTopics names one), every stream sorted by its
/// header stamp. A Metadata record "rownav" with key "manifest" (YAML, as write_mcap_recording
/// stores it) becomes Recording::manifest, so a converted rownav recording keeps its LiDAR mount.
/// Writing: clouds on /points, scans on /scan, IMU on /imu and the ground-truth poses on /odom
/// (a simulator's perfect odometry), messages in stamp order.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rownav/io/mcap_writer.hpp"
#include "rownav/io/recording.hpp"
#include "rownav/io/ros2_cloud.hpp"

namespace rownav::io {

/// The topic of each stream; empty: the first channel of that message type.
struct BagTopics {
  std::string cloud, scan, odom, imu;
};

/// "cloud=/points,odom=/odom,imu=/imu,scan=/scan" (any subset); std::invalid_argument naming
/// the bad item.
BagTopics parse_bag_topics(const std::string& spec);

/// True for an MCAP file (".mcap", case-insensitive): a ROS 2 bag.
bool is_mcap_file(const std::filesystem::path& file);

/// True for a file the bag readers take (".mcap", ".bag"; case-insensitive).
bool is_bag_file(const std::filesystem::path& file);

/// A reader of another bag format (ROS 1 `.bag`: ros/, built only with ROS).
using BagReader =
    std::function<Recording(const std::filesystem::path& file, const BagTopics& topics)>;
/// Registers `reader` for files ending in `extension` (".bag"; a null reader unregisters).
/// Not thread-safe: call at start-up.
void register_bag_reader(const std::string& extension, BagReader reader);

/// The stream of one message a bag writer writes (written as /points, /scan, /imu, /odom).
enum class BagStream : std::uint8_t { cloud, scan, imu, odom };
/// One message to write: its stamp, stream and index in that stream of the Recording.
struct BagEntry {
  double stamp;  ///< [s]
  BagStream stream;
  std::size_t index;
};
/// Every message of `rec` a bag writer writes (clouds, scans, IMU, the ground truth as
/// odometry), in stamp order (stable: a tie keeps that stream order). Shared by the MCAP and the
/// ROS 1 writers so that both bags hold the same messages in the same order.
std::vector<BagEntry> bag_entries(const Recording& rec);

/// A writer of another bag format (ROS 1 `.bag`: ros/, built only with ROS): the recording to
/// `file`, in the same streams and topics as write_mcap_recording.
using BagWriter = std::function<void(const Recording& rec, const std::filesystem::path& file)>;
/// Registers `writer` for files ending in `extension` (".bag"; null unregisters). Not
/// thread-safe: call at start-up.
void register_bag_writer(const std::string& extension, BagWriter writer);

/// InputError unless a bag can be written to `file`: ".mcap" always, others when a writer is
/// registered (".bag" only with ROS at build time). Said before any work.
void check_bag_writable(const std::filesystem::path& file);

/// Writes `rec` to `file` in the format of `target`'s extension (`file` may be a staging name
/// of `target`, io::OutputFile): ".mcap" write_mcap_recording, others a registered writer.
void write_bag_recording(const Recording& rec, const std::filesystem::path& file,
                         const std::filesystem::path& target);

/// Reads a bag by its extension: ".mcap" read_mcap_recording, others through a registered
/// reader; InputError when none is registered (".bag" without ROS at build time).
Recording read_bag_recording(const std::filesystem::path& file, const BagTopics& topics = {});

/// Reads an MCAP file. InputError on a malformed file or message (naming the topic and the
/// message index), or a topic of BagTopics that is not in the bag / not of the right type.
Recording read_mcap_recording(const std::filesystem::path& file, const BagTopics& topics = {});

/// Writes `rec` (its manifest as the "rownav" metadata) to `file`.
void write_mcap_recording(const Recording& rec, const std::filesystem::path& file,
                          const McapWriterConfig& config = {},
                          CloudTimeField time = CloudTimeField::velodyne_time);

}  // namespace rownav::io
