// read_cloud: the one translation unit that includes PCL (slow headers).
#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "cloud_header_check.hpp"
#include "rownav/io/cloud_io.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io {
namespace {

/// Value of one field element as a double, whatever its PCL datatype.
double field_value(const std::uint8_t* p, std::uint8_t datatype) {
  auto get = [p]<class T>(T) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return static_cast<double>(v);
  };
  switch (datatype) {
    case pcl::PCLPointField::INT8:
      return get(std::int8_t{});
    case pcl::PCLPointField::UINT8:
      return get(std::uint8_t{});
    case pcl::PCLPointField::INT16:
      return get(std::int16_t{});
    case pcl::PCLPointField::UINT16:
      return get(std::uint16_t{});
    case pcl::PCLPointField::INT32:
      return get(std::int32_t{});
    case pcl::PCLPointField::UINT32:
      return get(std::uint32_t{});
    case pcl::PCLPointField::FLOAT32:
      return get(float{});
    case pcl::PCLPointField::FLOAT64:
      return get(double{});
    default:
      return std::numeric_limits<double>::quiet_NaN();
  }
}

const pcl::PCLPointField* find_field(const pcl::PCLPointCloud2& c, std::string_view name) {
  for (const auto& f : c.fields)
    if (f.name == name) return &f;
  return nullptr;
}

bool is_integer_type(std::uint8_t t) {
  return t != pcl::PCLPointField::FLOAT32 && t != pcl::PCLPointField::FLOAT64;
}

// A coordinate, intensity or time as float: beyond float's range (or not finite) it is NaN, and
// the point is dropped with the other invalid ones (a double -> float cast out of range is
// undefined behaviour; the PCD fuzzer found one).
float to_float(double v) {
  return std::isfinite(v) && std::abs(v) <= double(std::numeric_limits<float>::max())
             ? static_cast<float>(v)
             : std::numeric_limits<float>::quiet_NaN();
}

// A ring or column index: a whole number in [0, 65535], else the file is not a LiDAR sweep.
std::uint16_t to_index(double v, const std::string& name, const char* field, std::size_t point) {
  if (!(v >= 0.0 && v <= double(std::numeric_limits<std::uint16_t>::max())))
    throw InputError(name, "point " + std::to_string(point),
                     std::string(field) + " " + std::to_string(v) + " is not in 0..65535");
  return static_cast<std::uint16_t>(v);
}

/// Per-point time [s] relative to the stamp; sets has_time and possibly the stamp.
void map_time(const pcl::PCLPointCloud2& c, std::vector<double>& times, core::PointCloud& out) {
  const pcl::PCLPointField* t = find_field(c, "t");
  double scale = 1.0;
  if (t && is_integer_type(t->datatype)) scale = 1e-9;  // Ouster: uint32 ns since sweep start
  if (!t) t = find_field(c, "time");
  if (!t) t = find_field(c, "timestamp");
  if (!t) return;
  out.has_time = true;
  const std::size_t n = static_cast<std::size_t>(c.width) * c.height;
  times.resize(n);
  double earliest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t row = i / c.width, col = i % c.width;
    const auto* p = c.data.data() + row * c.row_step + col * c.point_step + t->offset;
    times[i] = field_value(p, t->datatype) * scale;
    if (std::isfinite(times[i])) earliest = std::min(earliest, times[i]);
  }
  if (std::isfinite(earliest) && earliest > 1e6) {  // absolute timestamps
    out.stamp = earliest;
    for (auto& v : times) v -= earliest;
  }
}

core::PointCloud convert(const pcl::PCLPointCloud2& c, const std::string& name) {
  const auto* fx = find_field(c, "x");
  const auto* fy = find_field(c, "y");
  const auto* fz = find_field(c, "z");
  if (!fx || !fy || !fz) throw InputError(name, "", "no x / y / z fields");
  const auto* fi = find_field(c, "intensity");
  const auto* fr = find_field(c, "ring");
  const auto* fc = find_field(c, "column");
  core::PointCloud out;
  out.has_intensity = fi != nullptr;
  out.has_ring = fr != nullptr;
  std::vector<double> times;
  map_time(c, times, out);
  const std::size_t n = static_cast<std::size_t>(c.width) * c.height;
  if (c.data.size() < static_cast<std::size_t>(c.row_step) * c.height)
    throw InputError(name, "", "truncated point data");
  out.points.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto* base = c.data.data() + (i / c.width) * c.row_step + (i % c.width) * c.point_step;
    auto& p = out.points[i];
    p.x = to_float(field_value(base + fx->offset, fx->datatype));
    p.y = to_float(field_value(base + fy->offset, fy->datatype));
    p.z = to_float(field_value(base + fz->offset, fz->datatype));
    if (fi) p.intensity = to_float(field_value(base + fi->offset, fi->datatype));
    if (fr) p.ring = to_index(field_value(base + fr->offset, fr->datatype), name, "ring", i);
    if (fc) p.column = to_index(field_value(base + fc->offset, fc->datatype), name, "column", i);
    if (!times.empty()) p.time = to_float(times[i]);
  }
  out.drop_invalid();
  return out;
}

/// Silences PCL's console errors while reading: our InputError says it in one line.
class QuietPcl {
 public:
  QuietPcl() : level_(pcl::console::getVerbosityLevel()) {
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  }
  ~QuietPcl() { pcl::console::setVerbosityLevel(level_); }
  QuietPcl(const QuietPcl&) = delete;
  QuietPcl& operator=(const QuietPcl&) = delete;

 private:
  pcl::console::VERBOSITY_LEVEL level_;
};

}  // namespace

core::PointCloud read_cloud(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError(
        name, "",
        std::filesystem::exists(file, ec) ? "not a regular file" : "cannot open: no such file");
  if (std::filesystem::file_size(file, ec) == 0) throw InputError(name, "", "empty file");
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  pcl::PCLPointCloud2 cloud;
  core::PointCloud meta;
  const bool has_meta = ext == ".pcd" && detail::check_pcd_header(file, name, meta);
  if (ext == ".ply") detail::check_ply_header(file, name);
  {
    const QuietPcl quiet;
    if (ext == ".pcd") {
      pcl::PCDReader reader;
      if (reader.read(name, cloud) < 0) throw InputError(name, "", "not a valid PCD file");
    } else if (ext == ".ply") {
      pcl::PLYReader reader;
      if (reader.read(name, cloud) < 0) throw InputError(name, "", "not a valid PLY file");
    } else {
      throw InputError(name, "", "unknown cloud format '" + ext + "' (valid: .pcd, .ply)");
    }
  }
  core::PointCloud out = convert(cloud, name);
  if (has_meta) {  // written by write_cloud_pcd: restore what PCD has no field for
    out.stamp = meta.stamp;
    out.frame_id = meta.frame_id;
    out.has_intensity = meta.has_intensity;
    out.has_ring = meta.has_ring;
    out.has_time = meta.has_time;
  }
  return out;
}

}  // namespace rownav::io
