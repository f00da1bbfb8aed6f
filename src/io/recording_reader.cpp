#include <cmath>
#include <map>

#include "rownav/io/cloud_io.hpp"
#include "rownav/io/csv.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav/io/recording.hpp"
#include "rownav/io/yaml_config.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

/// Opens `rel` under dir if present and checks its header; false when absent.
bool open_csv(const fs::path& dir, const char* rel, const std::vector<std::string_view>& header,
              std::unique_ptr<CsvReader>& csv) {
  std::error_code ec;
  if (!fs::exists(dir / rel, ec)) return false;
  csv = std::make_unique<CsvReader>(dir / rel);
  if (!csv->next()) return false;
  csv->expect_header(header);
  return true;
}

template <class E>
E enum_cell(const CsvReader& csv, std::size_t i, std::string_view column) {
  E e{};
  if (!core::enum_from_name(csv.cell(i), e))
    csv.fail("unknown " + std::string(column) + " " + quote_for_message(csv.cell(i)) +
             " (valid: " + core::enum_name_list<E>() + ")");
  return e;
}

int int_cell(const CsvReader& csv, std::size_t i, std::string_view column) {
  const std::int64_t v = csv.integer(i, column);
  if (!std::in_range<int>(v))
    csv.fail("value out of range in column '" + std::string(column) + "'");
  return static_cast<int>(v);
}

/// Adds a RowTruth for row `id` from the offset / heading cells at i, i + 1 (when not empty).
void read_row_line(const CsvReader& csv, std::size_t i, int id, sim::GroundTruth& g) {
  if (csv.cell(i).empty() && csv.cell(i + 1).empty()) return;
  const double offset = csv.number(i, "offset"), heading = csv.number(i + 1, "heading");
  sim::RowTruth r;
  r.row = id;
  r.line_base.point = Eigen::Vector2d(0.0, offset);
  r.line_base.direction = Eigen::Vector2d(std::cos(heading), std::sin(heading));
  r.lateral = -r.line_base.signed_distance(Eigen::Vector2d::Zero());
  g.rows.push_back(r);
}

void read_ground_truth(const fs::path& dir, Recording& rec) {
  std::unique_ptr<CsvReader> csv;
  if (!open_csv(dir, "ground_truth.csv",
                {"stamp",
                 "x",
                 "y",
                 "theta",
                 "z",
                 "roll",
                 "pitch",
                 "v",
                 "vy",
                 "omega",
                 "place",
                 "block",
                 "corridor",
                 "left_row",
                 "right_row",
                 "lateral_error",
                 "heading_error",
                 "plants_crushed",
                 "left_offset",
                 "left_heading",
                 "right_offset",
                 "right_heading"},
                csv))
    return;
  while (csv->next()) {
    csv->expect_size(22);
    sim::GroundTruth g;
    const char* names[] = {"stamp", "x", "y", "theta", "z", "roll", "pitch", "v", "vy", "omega"};
    double* slots[] = {&g.stamp,    &g.T_world_base.x, &g.T_world_base.y, &g.T_world_base.theta,
                       &g.z,        &g.roll,           &g.pitch,          &g.twist.v,
                       &g.twist.vy, &g.twist.omega};
    for (std::size_t i = 0; i < 10; ++i) *slots[i] = csv->number(i, names[i]);
    g.place = enum_cell<sim::Place>(*csv, 10, "place");
    g.block = int_cell(*csv, 11, "block");
    g.corridor = int_cell(*csv, 12, "corridor");
    g.left_row = int_cell(*csv, 13, "left_row");
    g.right_row = int_cell(*csv, 14, "right_row");
    g.lateral_error = csv->number(15, "lateral_error");
    g.heading_error = csv->number(16, "heading_error");
    g.plants_crushed = int_cell(*csv, 17, "plants_crushed");
    read_row_line(*csv, 18, g.left_row, g);
    read_row_line(*csv, 20, g.right_row, g);
    rec.ground_truth.push_back(std::move(g));
  }
}

void read_sensors(const fs::path& dir, Recording& rec) {
  std::unique_ptr<CsvReader> csv;
  if (open_csv(dir, "encoders.csv", {"stamp", "left_ticks", "right_ticks", "steering_angle"}, csv))
    while (csv->next()) {
      csv->expect_size(4);
      rec.encoders.push_back({csv->number(0, "stamp"), csv->integer(1, "left_ticks"),
                              csv->integer(2, "right_ticks"), csv->number(3, "steering_angle")});
    }
  if (open_csv(dir, "imu.csv", {"stamp", "gx", "gy", "gz", "ax", "ay", "az"}, csv))
    while (csv->next()) {
      csv->expect_size(7);
      core::ImuSample s;
      s.stamp = csv->number(0, "stamp");
      s.angular_velocity = {csv->number(1, "gx"), csv->number(2, "gy"), csv->number(3, "gz")};
      s.linear_acceleration = {csv->number(4, "ax"), csv->number(5, "ay"), csv->number(6, "az")};
      rec.imu.push_back(s);
    }
  if (open_csv(dir, "gnss.csv", {"stamp", "valid", "east", "north", "up", "horizontal_std"}, csv))
    while (csv->next()) {
      csv->expect_size(6);
      core::GnssFix s;
      s.stamp = csv->number(0, "stamp");
      const auto valid = csv->integer(1, "valid");
      if (valid != 0 && valid != 1) csv->fail("column 'valid' must be 0 or 1");
      s.valid = valid == 1;
      s.position_enu = {csv->number(2, "east"), csv->number(3, "north"), csv->number(4, "up")};
      s.horizontal_std = csv->number(5, "horizontal_std");
      rec.gnss.push_back(s);
    }
}

void read_field(const fs::path& dir, Recording& rec) {
  std::unique_ptr<CsvReader> csv;
  std::map<int, std::size_t> row_index;
  if (open_csv(dir, "field/rows.csv", {"row", "block", "vertex", "x", "y", "half_width", "height"},
               csv))
    while (csv->next()) {
      csv->expect_size(7);
      const int id = int_cell(*csv, 0, "row");
      auto [it, fresh] = row_index.try_emplace(id, rec.rows.size());
      if (fresh) rec.rows.emplace_back().id = id;
      sim::Row& r = rec.rows[it->second];
      if (int_cell(*csv, 2, "vertex") != static_cast<int>(r.polyline.size()))
        csv->fail("vertices of row " + std::to_string(id) + " must be consecutive from 0");
      r.block = int_cell(*csv, 1, "block");
      r.polyline.emplace_back(csv->number(3, "x"), csv->number(4, "y"));
      r.half_width = csv->number(5, "half_width");
      r.height = csv->number(6, "height");
    }
  if (open_csv(dir, "field/plants.csv", {"kind", "row", "x", "y", "radius", "height"}, csv))
    while (csv->next()) {
      csv->expect_size(6);
      sim::Plant p;
      p.kind = enum_cell<sim::PlantKind>(*csv, 0, "kind");
      p.row = int_cell(*csv, 1, "row");
      p.position = {csv->number(2, "x"), csv->number(3, "y")};
      p.radius = csv->number(4, "radius");
      p.height = csv->number(5, "height");
      rec.plants.push_back(p);
    }
}

void read_lidar(const fs::path& dir, Recording& rec) {
  std::unique_ptr<CsvReader> csv;
  if (open_csv(dir, "lidar/frames.csv", {"index", "stamp", "file", "points"}, csv))
    while (csv->next()) {
      csv->expect_size(4);
      if (csv->integer(0, "index") != static_cast<std::int64_t>(rec.cloud_stamps.size()))
        csv->fail("frame indices must be consecutive from 0");
      const std::string file(csv->cell(2));
      if (file.empty() || file.find('/') != std::string::npos ||
          file.find("..") != std::string::npos)
        csv->fail("bad file name " + quote_for_message(file));
      rec.cloud_stamps.push_back(csv->number(1, "stamp"));
      rec.cloud_files.push_back(file);
      csv->integer(3, "points");
    }
  std::error_code ec;
  if (fs::exists(dir / "lidar/scans.csv", ec)) rec.scans = read_scans_csv(dir / "lidar/scans.csv");
}

}  // namespace

core::PointCloud Recording::cloud(std::size_t i) const {
  if (cloud_source) return cloud_source(i);
  core::PointCloud c = read_cloud(dir / "lidar" / cloud_files.at(i));
  c.stamp = cloud_stamps.at(i);
  return c;
}

Recording read_recording(const std::filesystem::path& dir) {
  Recording rec;
  rec.dir = dir;
  const fs::path manifest = dir / "manifest.yaml";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir.string(), "", "not a directory");
  rec.manifest = load_yaml_file(manifest);
  const YAML::Node& m = rec.manifest;  // const: operator[] must not insert keys
  if (!m.IsMap() || !m["format"] || !m["format"].IsScalar() ||
      m["format"].Scalar() != "rownav-recording")
    throw InputError(manifest.string(), "", "not a rownav recording (format: rownav-recording)");
  if (!m["version"] || !m["version"].IsScalar() || m["version"].Scalar() != "1")
    throw InputError(manifest.string(), detail::yaml_position(m["version"]),
                     "unsupported recording version (this build reads version 1)");
  read_lidar(dir, rec);
  read_sensors(dir, rec);
  read_ground_truth(dir, rec);
  read_field(dir, rec);
  return rec;
}

}  // namespace rownav::io
