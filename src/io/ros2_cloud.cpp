// sensor_msgs/msg/PointCloud2 in CDR <-> core::PointCloud (io/ros2_cloud.hpp).
#include "rownav/io/ros2_cloud.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>

#include "rownav/io/cdr.hpp"
#include "rownav/io/ros2_msgs.hpp"

namespace rownav::io {

namespace {

// sensor_msgs/PointField datatypes.
enum Datatype : std::uint8_t { INT8 = 1, UINT8, INT16, UINT16, INT32, UINT32, FLOAT32, FLOAT64 };
constexpr double kNanosecondsPerSecond = 1e9;
constexpr double kSecondsPerNanosecond = 1.0 / kNanosecondsPerSecond;
constexpr std::size_t kMaxTypeBytes = 8;

std::size_t type_size(std::uint8_t t) {
  switch (t) {
    case INT8: case UINT8: return 1;
    case INT16: case UINT16: return 2;
    case INT32: case UINT32: case FLOAT32: return 4;
    case FLOAT64: return 8;
    default: return 0;
  }
}

struct Field {
  std::string name;
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;
  std::uint32_t count = 0;
};

template <class T>
double as(const std::uint8_t* b) {
  T v;
  std::memcpy(&v, b, sizeof(T));
  return static_cast<double>(v);
}

/// The value of a field of the point at `p` (byte order of the message's data).
double value(const std::uint8_t* p, const Field& f, bool big_endian) {
  std::uint8_t b[kMaxTypeBytes];
  const std::size_t n = type_size(f.datatype);
  std::memcpy(b, p + f.offset, n);
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(b, b + n);
  switch (f.datatype) {
    case INT8: return as<std::int8_t>(b);
    case UINT8: return as<std::uint8_t>(b);
    case INT16: return as<std::int16_t>(b);
    case UINT16: return as<std::uint16_t>(b);
    case INT32: return as<std::int32_t>(b);
    case UINT32: return as<std::uint32_t>(b);
    case FLOAT32: return as<float>(b);
    default: return as<double>(b);
  }
}

std::vector<Field> read_fields(CdrReader& r) {
  std::vector<Field> fields(r.sequence_length(sizeof(std::uint32_t)));
  for (auto& f : fields) {
    f.name = r.string();
    f.offset = r.u32();
    f.datatype = r.u8();
    f.count = r.u32();
    if (type_size(f.datatype) == 0)
      throw CdrError("PointCloud2 field '" + f.name + "' has unknown datatype " +
                     std::to_string(f.datatype));
  }
  return fields;
}

/// The x, y, z, intensity, ring and time fields, each checked to lie inside the point.
struct Layout {
  std::optional<Field> x, y, z, intensity, ring, column, time;
  double time_scale = 1.0;   // to seconds
  bool time_absolute = false;
};

Layout layout(const std::vector<Field>& fields, std::uint32_t point_step) {
  Layout l;
  auto find = [&](const char* name) -> std::optional<Field> {
    for (const auto& f : fields) {
      if (f.name != name) continue;
      if (std::uint64_t{f.offset} + type_size(f.datatype) > point_step)
        throw CdrError("PointCloud2 field '" + f.name + "' at offset " + std::to_string(f.offset) +
                       " lies outside the " + std::to_string(point_step) + "-byte point");
      return f;
    }
    return std::nullopt;
  };
  l.x = find("x"), l.y = find("y"), l.z = find("z");
  if (!l.x || !l.y || !l.z) throw CdrError("PointCloud2 without x, y and z fields");
  l.intensity = find("intensity");
  l.ring = find("ring");
  l.column = find("column");  // rownav's own (an organised cloud's column index otherwise)
  if ((l.time = find("t"))) l.time_scale = kSecondsPerNanosecond;
  else if (!(l.time = find("time")) && (l.time = find("timestamp"))) l.time_absolute = true;
  return l;
}

}  // namespace

core::PointCloud decode_point_cloud2(std::span<const std::uint8_t> msg) {
  CdrReader r(msg);
  core::PointCloud c;
  const Ros2Header h = read_header(r);
  c.stamp = h.stamp;
  c.frame_id = h.frame_id;
  const std::uint64_t height = r.u32(), width = r.u32();
  const std::vector<Field> fields = read_fields(r);
  const bool big_endian = r.boolean();
  const std::uint64_t point_step = r.u32(), row_step = r.u32();
  const auto data = r.bytes(r.sequence_length(1));
  if (height * width == 0) return c;
  if (point_step == 0 || row_step < width * point_step ||
      (height - 1) * row_step + width * point_step > data.size())
    throw CdrError("PointCloud2 data (" + std::to_string(data.size()) + " bytes) does not hold " +
                   std::to_string(height) + " x " + std::to_string(width) + " points of " +
                   std::to_string(point_step) + " bytes (row_step " + std::to_string(row_step) +
                   ")");
  const Layout l = layout(fields, static_cast<std::uint32_t>(point_step));
  c.has_intensity = l.intensity.has_value();
  c.has_ring = l.ring.has_value();
  c.has_time = l.time.has_value();
  c.points.reserve(height * width);
  for (std::uint64_t row = 0; row < height; ++row) {
    for (std::uint64_t col = 0; col < width; ++col) {
      const std::uint8_t* p = data.data() + row * row_step + col * point_step;
      core::PointXYZIRT q;
      q.x = static_cast<float>(value(p, *l.x, big_endian));
      q.y = static_cast<float>(value(p, *l.y, big_endian));
      q.z = static_cast<float>(value(p, *l.z, big_endian));
      if (!q.finite()) continue;  // NaN: no return
      if (l.intensity) q.intensity = static_cast<float>(value(p, *l.intensity, big_endian));
      if (l.ring) q.ring = static_cast<std::uint16_t>(value(p, *l.ring, big_endian));
      if (l.column) q.column = static_cast<std::uint16_t>(value(p, *l.column, big_endian));
      else if (height > 1) q.column = static_cast<std::uint16_t>(col);
      if (l.time) {
        const double t = value(p, *l.time, big_endian);
        q.time = static_cast<float>(l.time_absolute ? t - c.stamp : t * l.time_scale);
      }
      c.points.push_back(q);
    }
  }
  return c;
}

namespace {

/// One field written: its name, type and the value of a point (stamp-relative time in [s]).
struct OutField {
  const char* name;
  std::uint8_t type;
  std::uint32_t offset = 0;
};

/// The fields of `cloud` that its flags say are meaningful, each aligned to its size.
std::vector<OutField> out_fields(const core::PointCloud& cloud, CloudTimeField time,
                                 std::uint32_t& step) {
  std::vector<OutField> f = {{"x", FLOAT32}, {"y", FLOAT32}, {"z", FLOAT32}};
  if (cloud.has_intensity) f.push_back({"intensity", FLOAT32});
  if (cloud.has_ring) f.push_back({"ring", UINT16}), f.push_back({"column", UINT16});
  if (cloud.has_time && time == CloudTimeField::ouster_t) f.push_back({"t", UINT32});
  if (cloud.has_time && time == CloudTimeField::velodyne_time) f.push_back({"time", FLOAT32});
  if (cloud.has_time && time == CloudTimeField::timestamp) f.push_back({"timestamp", FLOAT64});
  step = 0;
  std::uint32_t widest = 1;
  for (auto& x : f) {
    const auto n = static_cast<std::uint32_t>(type_size(x.type));
    step = (step + n - 1) / n * n;
    x.offset = step;
    step += n;
    widest = std::max(widest, n);
  }
  step = (step + widest - 1) / widest * widest;  // every point aligned like its widest field
  return f;
}

template <class T>
void put(std::uint8_t* at, T v) {
  std::memcpy(at, &v, sizeof(T));  // host byte order (is_bigendian says which)
}

void put_point(std::uint8_t* at, const OutField& f, const core::PointXYZIRT& p, double stamp) {
  const std::string_view n = f.name;
  std::uint8_t* d = at + f.offset;
  if (n == "x") put(d, p.x);
  else if (n == "y") put(d, p.y);
  else if (n == "z") put(d, p.z);
  else if (n == "intensity") put(d, p.intensity);
  else if (n == "ring") put(d, p.ring);
  else if (n == "column") put(d, p.column);
  else if (n == "time") put(d, p.time);
  else if (n == "timestamp") put(d, stamp + static_cast<double>(p.time));
  else put(d, static_cast<std::uint32_t>(std::llround(std::max(0.0f, p.time) * kNanosecondsPerSecond)));
}

}  // namespace

std::vector<std::uint8_t> encode_point_cloud2(const core::PointCloud& cloud, CloudTimeField time,
                                              std::uint32_t height) {
  if (height == 0 || cloud.size() % height != 0)
    throw std::invalid_argument("encode_point_cloud2: " + std::to_string(cloud.size()) +
                                " points are not a multiple of height " + std::to_string(height));
  std::uint32_t step = 0;
  const std::vector<OutField> fields = out_fields(cloud, time, step);
  const auto width = static_cast<std::uint32_t>(cloud.size() / height);
  CdrWriter w;
  write_header(w, cloud.stamp, cloud.frame_id);
  w.u32(height);
  w.u32(width);
  w.u32(static_cast<std::uint32_t>(fields.size()));
  for (const auto& f : fields) w.string(f.name), w.u32(f.offset), w.u8(f.type), w.u32(1);
  w.boolean(std::endian::native == std::endian::big);
  w.u32(step);
  w.u32(step * width);
  std::vector<std::uint8_t> d(std::size_t{step} * cloud.size(), 0);
  for (std::size_t i = 0; i < cloud.size(); ++i)
    for (const auto& f : fields) put_point(d.data() + i * step, f, cloud.points[i], cloud.stamp);
  w.u32(static_cast<std::uint32_t>(d.size()));
  w.bytes(d);
  w.boolean(false);  // is_dense: rownav clouds hold only finite points, but say nothing
  return w.data();
}

}  // namespace rownav::io
