// PCD writing and CSV points / scans (no PCL here: read_cloud is in cloud_io_pcl.cpp).
#include <cstring>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "rownav/io/cloud_io.hpp"
#include "rownav/io/csv.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io {
namespace {

std::string pcd_header(const core::PointCloud& cloud, bool binary) {
  const bool none = !cloud.has_intensity && !cloud.has_ring && !cloud.has_time;
  std::string frame = cloud.frame_id;
  for (char& c : frame)
    if (c == '\n' || c == '\r') c = '_';
  const std::size_t n = cloud.points.size();
  std::ostringstream h;
  h << "# .PCD v0.7 - Point Cloud Data file format\n# rownav stamp=" << format_double(cloud.stamp)
    << " flags=" << (none ? "-" : "") << (cloud.has_intensity ? "i" : "")
    << (cloud.has_ring ? "r" : "") << (cloud.has_time ? "t" : "") << " frame_id=" << frame
    << "\nVERSION 0.7\nFIELDS x y z intensity ring column time\nSIZE 4 4 4 4 2 2 4\n"
       "TYPE F F F F U U F\nCOUNT 1 1 1 1 1 1 1\nWIDTH "
    << n << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << n << "\nDATA "
    << (binary ? "binary" : "ascii") << '\n';
  return h.str();
}

void write_binary_points(std::ostream& out, const std::vector<core::PointXYZIRT>& points) {
  constexpr std::size_t kStep = 24;
  std::vector<char> buf(points.size() * kStep);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    char* b = buf.data() + i * kStep;
    std::memcpy(b + 0, &p.x, 4);
    std::memcpy(b + 4, &p.y, 4);
    std::memcpy(b + 8, &p.z, 4);
    std::memcpy(b + 12, &p.intensity, 4);
    std::memcpy(b + 16, &p.ring, 2);
    std::memcpy(b + 18, &p.column, 2);
    std::memcpy(b + 20, &p.time, 4);
  }
  out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
}

/// Column indices of a points CSV; npos when absent.
struct PointColumns {
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  std::size_t frame = npos, stamp = npos, x = npos, y = npos, z = npos, intensity = npos;
  std::size_t count = 0;
};

PointColumns header_columns(const CsvReader& csv) {
  PointColumns c;
  c.count = csv.size();
  for (std::size_t i = 0; i < csv.size(); ++i) {
    const auto name = csv.cell(i);
    std::size_t* slot = name == "frame"       ? &c.frame
                        : name == "stamp"     ? &c.stamp
                        : name == "x"         ? &c.x
                        : name == "y"         ? &c.y
                        : name == "z"         ? &c.z
                        : name == "intensity" ? &c.intensity
                                              : nullptr;
    if (!slot)
      // Quoted and escaped: a header cell may hold a '\r' or control bytes (points_csv_fuzz).
      csv.fail("unknown column " + quote_for_message(name) +
               " (valid: frame, stamp, x, y, z, intensity)");
    *slot = i;
  }
  if (c.x == PointColumns::npos || c.y == PointColumns::npos) csv.fail("need columns x and y");
  return c;
}

PointColumns headerless_columns(const CsvReader& csv) {
  PointColumns c;
  c.count = csv.size();
  if (c.count == 2)
    c.x = 0, c.y = 1;
  else if (c.count == 3)
    c.x = 0, c.y = 1, c.z = 2;
  else if (c.count == 4)
    c.frame = 0, c.x = 1, c.y = 2, c.z = 3;
  else
    csv.fail("expected 2 (x,y), 3 (x,y,z) or 4 (frame,x,y,z) columns, got " +
             std::to_string(c.count));
  return c;
}

bool all_numbers(const CsvReader& csv) {
  double v = 0.0;
  for (const auto cell : csv.cells())
    if (!parse_double(cell, v)) return false;
  return true;
}

}  // namespace

void write_cloud_pcd(const std::filesystem::path& file, const core::PointCloud& cloud,
                     bool binary) {
  std::ofstream out(file, std::ios::binary);
  out << pcd_header(cloud, binary);
  if (binary) {
    write_binary_points(out, cloud.points);
  } else {
    for (const auto& p : cloud.points)
      out << format_float(p.x) << ' ' << format_float(p.y) << ' ' << format_float(p.z) << ' '
          << format_float(p.intensity) << ' ' << p.ring << ' ' << p.column << ' '
          << format_float(p.time) << '\n';
  }
  out.close();
  if (!out) throw std::runtime_error(file.string() + ": cannot write");
}

std::vector<core::PointCloud> read_points_csv(const std::filesystem::path& file) {
  CsvReader csv(file);
  std::vector<core::PointCloud> clouds;
  if (!csv.next()) return clouds;
  const bool header = !all_numbers(csv);
  const PointColumns c = header ? header_columns(csv) : headerless_columns(csv);
  if (header && !csv.next()) return clouds;
  std::unordered_map<std::string, std::size_t> index;  // frame cell -> cloud
  std::string_view last_frame;
  std::size_t current = 0;
  do {
    csv.expect_size(c.count);
    const std::string_view frame = c.frame == PointColumns::npos ? "" : csv.cell(c.frame);
    if (clouds.empty() || frame != last_frame) {
      auto [it, fresh] = index.try_emplace(std::string(frame), clouds.size());
      if (fresh) {
        core::PointCloud cloud;
        cloud.has_intensity = c.intensity != PointColumns::npos;
        cloud.stamp = c.stamp != PointColumns::npos   ? csv.number(c.stamp, "stamp")
                      : c.frame != PointColumns::npos ? csv.number(c.frame, "frame")
                                                      : 0.0;
        clouds.push_back(std::move(cloud));
      }
      current = it->second;
      last_frame = frame;
    }
    core::PointXYZIRT p;
    p.x = csv.number_f(c.x, "x");
    p.y = csv.number_f(c.y, "y");
    if (c.z != PointColumns::npos) p.z = csv.number_f(c.z, "z");
    if (c.intensity != PointColumns::npos) p.intensity = csv.number_f(c.intensity, "intensity");
    if (p.finite()) clouds[current].points.push_back(p);
  } while (csv.next());
  return clouds;
}

std::vector<core::Scan2D> read_scans_csv(const std::filesystem::path& file) {
  CsvReader csv(file);
  std::vector<core::Scan2D> scans;
  if (!csv.next()) return scans;
  csv.expect_header({"stamp", "angle_min", "angle_increment", "range_min", "range_max", "ranges"});
  while (csv.next()) {
    if (csv.size() < 5) csv.fail("expected at least 5 columns, got " + std::to_string(csv.size()));
    core::Scan2D s;
    s.stamp = csv.number(0, "stamp");
    s.angle_min = csv.number(1, "angle_min");
    s.angle_increment = csv.number(2, "angle_increment");
    s.range_min = csv.number(3, "range_min");
    s.range_max = csv.number(4, "range_max");
    if (csv.size() == 6 && csv.cell(5).empty()) {  // a scan without beams
      scans.push_back(std::move(s));
      continue;
    }
    s.ranges.reserve(csv.size() - 5);
    for (std::size_t i = 5; i < csv.size(); ++i) s.ranges.push_back(csv.number_f(i, "ranges"));
    scans.push_back(std::move(s));
  }
  return scans;
}

void write_scan_csv_row(std::ostream& out, const core::Scan2D& s) {
  out << format_double(s.stamp) << ',' << format_double(s.angle_min) << ','
      << format_double(s.angle_increment) << ',' << format_double(s.range_min) << ','
      << format_double(s.range_max);
  if (s.ranges.empty()) out << ',';
  for (const float r : s.ranges) out << ',' << format_float(r);
  out << '\n';
}

void write_scans_csv(const std::filesystem::path& file, const std::vector<core::Scan2D>& scans) {
  std::ofstream out(file);
  out << kScansCsvHeader << '\n';
  for (const auto& s : scans) write_scan_csv_row(out, s);
  out.close();
  if (!out) throw std::runtime_error(file.string() + ": cannot write");
}

}  // namespace rownav::io
