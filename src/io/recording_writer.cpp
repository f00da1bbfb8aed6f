#include <cstdio>
#include <stdexcept>

#include "rownav/io/cloud_io.hpp"
#include "rownav/io/csv.hpp"
#include "rownav/io/recording.hpp"
#include "rownav/io/yaml_config.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

std::string d(double v) {
  return format_double(v);
}

/// Writes ",<offset>,<heading>" of row `id` in gt.rows, or ",," when absent.
void write_row_line(std::ostream& out, const sim::GroundTruth& gt, int id) {
  for (const auto& r : gt.rows) {
    if (r.row != id || id < 0) continue;
    const auto& l = r.line_base;
    if (l.direction.x() == 0.0) break;  // parallel to y: no offset at x = 0
    out << ',' << d(l.y_at(0.0)) << ',' << d(l.heading());
    return;
  }
  out << ",,";
}

[[noreturn]] void fail(const fs::path& p, const std::string& why) {
  throw std::runtime_error(p.string() + ": " + why);
}

}  // namespace

RecordingWriter::RecordingWriter(const fs::path& dir, YAML::Node manifest, bool overwrite)
    : manifest_(manifest) {
  if (manifest_ && !manifest_.IsNull() && !manifest_.IsMap()) fail(dir, "manifest must be a map");
  out_ = std::make_unique<OutputDir>(dir, overwrite, "recording");
  partial_ = out_->staging();
}

RecordingWriter::~RecordingWriter() {
  streams_.clear();  // closed before the staging directory is removed (uncommitted)
}

std::ofstream& RecordingWriter::stream(const std::string& rel, const char* header) {
  for (auto& [name, s] : streams_)
    if (name == rel) return *s;
  const fs::path path = partial_ / rel;
  fs::create_directories(path.parent_path());
  auto s = std::make_unique<std::ofstream>(path);
  if (!*s) fail(path, "cannot write");
  *s << header << '\n';
  streams_.emplace_back(rel, std::move(s));
  return *streams_.back().second;
}

void RecordingWriter::write_cloud(const core::PointCloud& cloud) {
  char name[32];
  std::snprintf(name, sizeof name, "%06zu.pcd", clouds_);
  auto& index = stream("lidar/frames.csv", "index,stamp,file,points");
  write_cloud_pcd(partial_ / "lidar" / name, cloud, true);
  index << clouds_ << ',' << d(cloud.stamp) << ',' << name << ',' << cloud.size() << '\n';
  ++clouds_;
}

void RecordingWriter::write_scan(const core::Scan2D& scan) {
  write_scan_csv_row(stream("lidar/scans.csv", kScansCsvHeader.data()), scan);
}

void RecordingWriter::write_encoders(const core::WheelEncoderSample& s) {
  stream("encoders.csv", "stamp,left_ticks,right_ticks,steering_angle")
      << d(s.stamp) << ',' << s.left_ticks << ',' << s.right_ticks << ',' << d(s.steering_angle)
      << '\n';
}

void RecordingWriter::write_imu(const core::ImuSample& s) {
  const auto &g = s.angular_velocity, &a = s.linear_acceleration;
  stream("imu.csv", "stamp,gx,gy,gz,ax,ay,az")
      << d(s.stamp) << ',' << d(g.x()) << ',' << d(g.y()) << ',' << d(g.z()) << ',' << d(a.x())
      << ',' << d(a.y()) << ',' << d(a.z()) << '\n';
}

void RecordingWriter::write_gnss(const core::GnssFix& s) {
  const auto& p = s.position_enu;
  stream("gnss.csv", "stamp,valid,east,north,up,horizontal_std")
      << d(s.stamp) << ',' << (s.valid ? 1 : 0) << ',' << d(p.x()) << ',' << d(p.y()) << ','
      << d(p.z()) << ',' << d(s.horizontal_std) << '\n';
}

void RecordingWriter::write_ground_truth(const sim::GroundTruth& g) {
  auto& out = stream("ground_truth.csv",
                     "stamp,x,y,theta,z,roll,pitch,v,vy,omega,place,block,corridor,left_row,"
                     "right_row,lateral_error,heading_error,plants_crushed,left_offset,"
                     "left_heading,right_offset,right_heading");
  const auto& T = g.T_world_base;
  out << d(g.stamp) << ',' << d(T.x) << ',' << d(T.y) << ',' << d(T.theta) << ',' << d(g.z) << ','
      << d(g.roll) << ',' << d(g.pitch) << ',' << d(g.twist.v) << ',' << d(g.twist.vy) << ','
      << d(g.twist.omega) << ',' << core::enum_name(g.place) << ',' << g.block << ',' << g.corridor
      << ',' << g.left_row << ',' << g.right_row << ',' << d(g.lateral_error) << ','
      << d(g.heading_error) << ',' << g.plants_crushed;
  write_row_line(out, g, g.left_row);
  write_row_line(out, g, g.right_row);
  out << '\n';
}

void RecordingWriter::write_field(const sim::Field& field) {
  if (field_written_) throw std::logic_error("RecordingWriter::write_field called twice");
  field_written_ = true;
  auto& rows = stream("field/rows.csv", "row,block,vertex,x,y,half_width,height");
  for (const auto& r : field.rows)
    for (std::size_t v = 0; v < r.polyline.size(); ++v)
      rows << r.id << ',' << r.block << ',' << v << ',' << d(r.polyline[v].x()) << ','
           << d(r.polyline[v].y()) << ',' << d(r.half_width) << ',' << d(r.height) << '\n';
  auto& plants = stream("field/plants.csv", "kind,row,x,y,radius,height");
  for (const auto& p : field.plants)
    plants << core::enum_name(p.kind) << ',' << p.row << ',' << d(p.position.x()) << ','
           << d(p.position.y()) << ',' << d(p.radius) << ',' << d(p.height) << '\n';
}

void RecordingWriter::commit() {
  if (out_->committed()) throw std::logic_error("RecordingWriter::commit called twice");
  for (auto& [name, s] : streams_) {
    s->close();
    if (!*s) fail(partial_ / name, "write failed (disk full?)");
  }
  streams_.clear();
  YAML::Node m(YAML::NodeType::Map);
  m["format"] = "rownav-recording";
  m["version"] = 1;
  if (manifest_ && manifest_.IsMap())
    for (const auto& kv : manifest_)
      if (kv.first.Scalar() != "format" && kv.first.Scalar() != "version")
        m[kv.first.Scalar()] = kv.second;
  save_yaml(partial_ / "manifest.yaml", m);
  out_->commit();
}

}  // namespace rownav::io
