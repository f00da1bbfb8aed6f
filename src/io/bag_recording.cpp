// ROS 2 bags (MCAP) read as recordings and recordings written as bags (io/bag_recording.hpp).
#include "rownav/io/bag_recording.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <sstream>

#include "rownav/io/input_error.hpp"
#include "rownav/io/mcap_reader.hpp"
#include "rownav/io/ros2_msgs.hpp"

namespace rownav::io {

namespace {

constexpr const char* kMetadataName = "rownav";
constexpr const char* kManifestKey = "manifest";
constexpr double kNanosecondsPerSecond = 1e9;

/// The channel chosen for each stream: the named topic, else the first of the type.
class TopicChoice {
 public:
  TopicChoice(const BagTopics& t) : t_(t) {}
  /// True when `m` belongs to the stream of type `type` named `wanted`.
  bool take(const McapChannel& c, const char* type, const std::string& wanted, int& chosen) {
    if (chosen >= 0) return chosen == c.id;
    const bool named = !wanted.empty();
    if (named ? c.topic != wanted : c.schema_name != type) return false;
    chosen = c.id;
    return true;
  }
  const BagTopics& t_;
  int cloud = -1, scan = -1, odom = -1, imu = -1;
};

void check_type(const McapChannel& c, const char* type, const std::filesystem::path& file) {
  if (c.schema_name != type)
    throw InputError(file.string(), "topic " + c.topic,
                     "is " + (c.schema_name.empty() ? "schema-less" : c.schema_name) + ", not " +
                         type);
  if (c.message_encoding != "cdr")
    throw InputError(file.string(), "topic " + c.topic,
                     "message encoding '" + c.message_encoding + "' (only ROS 2 cdr is read)");
}

template <class T>
void sort_by_stamp(std::vector<T>& v) {
  std::stable_sort(v.begin(), v.end(), [](const T& a, const T& b) { return a.stamp < b.stamp; });
}

void check_named(const std::string& topic, int chosen, const char* what,
                 const std::filesystem::path& file) {
  if (!topic.empty() && chosen < 0)
    throw InputError(file.string(), "", "--topics " + std::string(what) + "=" + topic +
                                            ": no such topic in the bag");
}

std::uint64_t to_ns(double stamp) {
  return static_cast<std::uint64_t>(std::llround(std::max(0.0, stamp) * kNanosecondsPerSecond));
}

}  // namespace

BagTopics parse_bag_topics(const std::string& spec) {
  BagTopics t;
  std::stringstream ss(spec);
  for (std::string item; std::getline(ss, item, ',');) {
    const auto eq = item.find('=');
    const std::string key = item.substr(0, eq);
    if (eq == std::string::npos || eq + 1 == item.size())
      throw std::invalid_argument("--topics: '" + item + "' is not stream=/topic");
    const std::string topic = item.substr(eq + 1);
    if (key == "cloud") t.cloud = topic;
    else if (key == "scan") t.scan = topic;
    else if (key == "odom") t.odom = topic;
    else if (key == "imu") t.imu = topic;
    else
      throw std::invalid_argument("--topics: unknown stream '" + key +
                                  "' (cloud, scan, odom, imu)");
  }
  return t;
}

namespace {

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::map<std::string, BagReader>& bag_readers() {
  static std::map<std::string, BagReader> readers;
  return readers;
}

std::map<std::string, BagWriter>& bag_writers() {
  static std::map<std::string, BagWriter> writers;
  return writers;
}

}  // namespace

bool is_mcap_file(const std::filesystem::path& file) {
  return lower_extension(file) == ".mcap";
}

bool is_bag_file(const std::filesystem::path& file) {
  const std::string ext = lower_extension(file);
  return ext == ".mcap" || ext == ".bag" || bag_readers().count(ext) > 0;
}

void register_bag_reader(const std::string& extension, BagReader reader) {
  if (reader) bag_readers()[extension] = std::move(reader);
  else bag_readers().erase(extension);
}

void register_bag_writer(const std::string& extension, BagWriter writer) {
  if (writer) bag_writers()[extension] = std::move(writer);
  else bag_writers().erase(extension);
}

void check_bag_writable(const std::filesystem::path& file) {
  const std::string ext = lower_extension(file);
  if (ext == ".mcap" || bag_writers().count(ext) > 0) return;
  if (ext == ".bag")
    throw InputError(file.string(), "",
                     "ROS 1 bags need librosbag: rownav was built without ROS (docs/bags.md); "
                     "write a .mcap or rebuild with -DROWNAV_BUILD_ROS=ON");
  throw InputError(file.string(), "", "unknown bag format '" + ext + "' (.mcap or .bag)");
}

void write_bag_recording(const Recording& rec, const std::filesystem::path& file,
                         const std::filesystem::path& target) {
  const std::string ext = lower_extension(target);
  if (ext == ".mcap") return write_mcap_recording(rec, file);
  check_bag_writable(target);
  try {
    bag_writers().at(ext)(rec, file);
  } catch (const InputError& e) {  // name the user's file, not the staging one
    throw InputError(target.string(), e.position(), e.reason());
  }
}

Recording read_bag_recording(const std::filesystem::path& file, const BagTopics& topics) {
  const std::string ext = lower_extension(file);
  if (ext == ".mcap") return read_mcap_recording(file, topics);
  const auto it = bag_readers().find(ext);
  if (it == bag_readers().end())
    throw InputError(file.string(), "",
                     "ROS 1 bags need librosbag: rownav was built without ROS (docs/bags.md); "
                     "convert the bag to MCAP or rebuild with -DROWNAV_BUILD_ROS=ON");
  return it->second(file, topics);
}

namespace {

/// Clouds in stamp order; each decoded again from the bag when replayed (not kept in memory).
void set_cloud_source(Recording& rec, const std::vector<McapRef>& refs,
                      const std::shared_ptr<McapReader>& reader, const std::filesystem::path& file) {
  std::vector<std::size_t> order(refs.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return rec.cloud_stamps[a] < rec.cloud_stamps[b];
  });
  std::vector<McapRef> sorted_refs;
  std::vector<double> sorted_stamps;
  for (const std::size_t i : order)
    sorted_refs.push_back(refs[i]), sorted_stamps.push_back(rec.cloud_stamps[i]);
  rec.cloud_stamps = std::move(sorted_stamps);
  rec.cloud_files.assign(rec.cloud_stamps.size(), "");
  rec.cloud_source = [reader, sorted_refs, file](std::size_t i) {
    try {
      return decode_point_cloud2(reader->message_data(sorted_refs.at(i)));
    } catch (const CdrError& e) {
      throw InputError(file.string(), "cloud " + std::to_string(i), e.what());
    }
  };
}

}  // namespace

Recording read_mcap_recording(const std::filesystem::path& file, const BagTopics& topics) {
  auto reader = std::make_shared<McapReader>(file);
  Recording rec;
  rec.dir = file;
  TopicChoice choice(topics);
  std::vector<McapRef> refs;
  std::size_t index = 0;
  reader->read([&](const McapMessage& m) {
    const McapChannel& c = *m.channel;
    try {
      if (choice.take(c, kRos2PointCloud2, topics.cloud, choice.cloud)) {
        check_type(c, kRos2PointCloud2, file);
        CdrReader header(m.data);  // the points are decoded when the replay asks for them
        rec.cloud_stamps.push_back(read_header(header).stamp);
        refs.push_back(m.ref);
      } else if (choice.take(c, kRos2LaserScan, topics.scan, choice.scan)) {
        check_type(c, kRos2LaserScan, file);
        rec.scans.push_back(decode_laser_scan(m.data));
      } else if (choice.take(c, kRos2Imu, topics.imu, choice.imu)) {
        check_type(c, kRos2Imu, file);
        rec.imu.push_back(decode_imu(m.data));
      } else if (choice.take(c, kRos2Odometry, topics.odom, choice.odom)) {
        check_type(c, kRos2Odometry, file);
        rec.odometry.push_back(decode_odometry(m.data));
      }
    } catch (const CdrError& e) {
      throw InputError(file.string(), "topic " + c.topic + " message " + std::to_string(index),
                       e.what());
    }
    ++index;
  });
  check_named(topics.cloud, choice.cloud, "cloud", file);
  check_named(topics.scan, choice.scan, "scan", file);
  check_named(topics.imu, choice.imu, "imu", file);
  check_named(topics.odom, choice.odom, "odom", file);
  sort_by_stamp(rec.scans), sort_by_stamp(rec.imu), sort_by_stamp(rec.odometry);
  set_cloud_source(rec, refs, reader, file);
  const auto meta = reader->metadata().find(kMetadataName);
  if (meta != reader->metadata().end() && meta->second.count(kManifestKey)) {
    try {
      rec.manifest = YAML::Load(meta->second.at(kManifestKey));
    } catch (const YAML::Exception& e) {
      throw InputError(file.string(), "metadata rownav", std::string("manifest: ") + e.what());
    }
  }
  return rec;
}

std::vector<BagEntry> bag_entries(const Recording& rec) {
  std::vector<BagEntry> e;
  for (std::size_t i = 0; i < rec.cloud_count(); ++i)
    e.push_back({rec.cloud_stamps[i], BagStream::cloud, i});
  for (std::size_t i = 0; i < rec.scans.size(); ++i)
    e.push_back({rec.scans[i].stamp, BagStream::scan, i});
  for (std::size_t i = 0; i < rec.imu.size(); ++i) e.push_back({rec.imu[i].stamp, BagStream::imu, i});
  for (std::size_t i = 0; i < rec.ground_truth.size(); ++i)
    e.push_back({rec.ground_truth[i].stamp, BagStream::odom, i});
  std::stable_sort(e.begin(), e.end(),
                   [](const BagEntry& a, const BagEntry& b) { return a.stamp < b.stamp; });
  return e;
}

void write_mcap_recording(const Recording& rec, const std::filesystem::path& file,
                          const McapWriterConfig& config, CloudTimeField time) {
  McapWriter w(file, config);
  if (rec.manifest && !rec.manifest.IsNull()) {
    YAML::Emitter e;
    e << rec.manifest;
    w.write_metadata(kMetadataName, {{kManifestKey, e.c_str()}});
  }
  // One channel per BagStream, in its order.
  constexpr std::size_t kStreams = 4;
  const char* types[kStreams] = {kRos2PointCloud2, kRos2LaserScan, kRos2Imu, kRos2Odometry};
  const char* topics[kStreams] = {"/points", "/scan", "/imu", "/odom"};
  std::uint16_t channel[kStreams];
  for (std::size_t s = 0; s < kStreams; ++s)
    channel[s] = w.add_channel(w.add_schema(types[s], "ros2msg", ""), topics[s], "cdr");
  for (const BagEntry& e : bag_entries(rec)) {
    std::vector<std::uint8_t> data;
    if (e.stream == BagStream::cloud) data = encode_point_cloud2(rec.cloud(e.index), time);
    else if (e.stream == BagStream::scan) data = encode_laser_scan(rec.scans[e.index]);
    else if (e.stream == BagStream::imu) data = encode_imu(rec.imu[e.index]);
    else {
      const sim::GroundTruth& g = rec.ground_truth[e.index];
      data = encode_odometry({g.stamp, g.T_world_base, g.twist});
    }
    w.write(channel[static_cast<std::size_t>(e.stream)], to_ns(e.stamp), data);
  }
  w.close();
}

}  // namespace rownav::io
