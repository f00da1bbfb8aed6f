// `rownav detect`: runs a row detector on a cloud, a points CSV, a scans CSV or a recording.
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands.hpp"
#include "rownav/io/canvas.hpp"
#include "rownav/io/recording_replay.hpp"
#include "rownav/io/safe_output.hpp"
#include "rownav/navigate/nav_stack.hpp"
#include "detect_picture.hpp"
#include "setup.hpp"
#include "rownav/core/angle.hpp"
#include "rownav/detect/pipeline.hpp"
#include "rownav/io/bag_recording.hpp"
#include "rownav/io/cloud_io.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav/io/recording.hpp"
#include "rownav/io/sim_setup.hpp"

namespace rownav::app {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

struct DetectArgs {
  std::string detector;
  fs::path config, in, out, svg;
  std::vector<double> mount;  // x, y, z [m], roll, pitch, yaw [deg]
  std::string topics;         // bags: stream=/topic,...
  int svg_frame = 0;
  bool overwrite = false;
};

json row_json(const core::RowLine& r) {
  return {{"offset", r.offset},   {"heading_deg", core::rad2deg(r.heading)},
          {"x_min", r.x_min},     {"x_max", r.x_max},
          {"support", r.support}, {"rms", r.rms}};
}

json side_json(const core::RowObservation& obs, int index) {
  if (index < 0 || index >= static_cast<int>(obs.rows.size())) return nullptr;
  const auto& r = obs.rows[static_cast<std::size_t>(index)];
  return {{"index", index}, {"offset", r.offset}, {"heading_deg", core::rad2deg(r.heading)}};
}

json observation_json(const core::RowObservation& obs, std::optional<std::int64_t> frame) {
  json j;
  if (frame) j["frame"] = *frame;
  j["stamp"] = obs.stamp;
  j["status"] = std::string(core::enum_name(obs.status));
  j["confidence"] = obs.confidence;
  j["heading_deg"] = core::rad2deg(obs.heading);
  j["rows"] = json::array();
  for (const auto& r : obs.rows) j["rows"].push_back(row_json(r));
  j["left"] = side_json(obs, obs.left);
  j["right"] = side_json(obs, obs.right);
  j["corridor"] = nullptr;
  if (obs.corridor)
    j["corridor"] = {{"offset", obs.corridor->offset},
                     {"heading_deg", core::rad2deg(obs.corridor->heading)},
                     {"width", obs.corridor->width}};
  return j;
}

// Columns of a points CSV, from its first line (the rules of io::read_points_csv).
struct CsvShape {
  bool frame = false, stamp = false, z = false, scans = false;
};

CsvShape sniff_csv(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw io::InputError(file.string(), "", "cannot open");
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  CsvShape s;
  if (line.rfind(io::kScansCsvHeader, 0) == 0) {
    s.scans = true;
    return s;
  }
  std::vector<std::string> cells;
  std::stringstream ss(line);
  for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
  bool header = false;
  for (const auto& c : cells) {
    char* end = nullptr;
    std::strtod(c.c_str(), &end);
    header |= c.empty() || *end != '\0';
  }
  if (header) {
    for (const auto& c : cells) {
      s.frame |= c == "frame";
      s.stamp |= c == "stamp";
      s.z |= c == "z";
    }
  } else {
    s.z = cells.size() >= 3;
    s.frame = cells.size() == 4;
  }
  return s;
}

// One detected frame: its observation, its points (for the picture) and its frame number.
using Emit = std::function<void(const detect::DetectionPipeline&, const core::RowObservation&,
                                std::optional<std::int64_t>)>;

void run_points_csv(const fs::path& in, detect::DetectionPipeline& p, const Emit& emit) {
  const CsvShape shape = sniff_csv(in);
  const Eigen::Isometry2f T = detect::planar_mount(p.T_base_lidar()).cast<float>();
  std::vector<Eigen::Vector2f> pts;
  for (const auto& cloud : io::read_points_csv(in)) {
    std::optional<std::int64_t> frame;
    if (shape.frame && !shape.stamp) frame = std::llround(cloud.stamp);
    if (shape.z) {
      emit(p, p.process(cloud), frame);
      continue;
    }
    pts.clear();  // x, y only: a planar sensor, mounted in the plane
    for (const auto& q : cloud.points) pts.push_back(T * Eigen::Vector2f(q.x, q.y));
    emit(p, p.process_points(pts, cloud.stamp), frame);
  }
}

void run_recording(const DetectArgs& a, const Emit& emit) {
  const bool bag = io::is_bag_file(a.in);
  const io::Recording rec = bag ? io::read_bag_recording(a.in, io::parse_bag_topics(a.topics))
                                : io::read_recording(a.in);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (!a.mount.empty()) {
    T = mount_transform(a.mount);
  } else if (bag && !rec.manifest["sensors"]) {
    // A bag without rownav's manifest: the LiDAR frame is the base frame (as for a .pcd).
  } else {
    const std::string manifest = bag ? a.in.string() : (a.in / "manifest.yaml").string();
    if (!rec.manifest["sensors"] || !rec.manifest["sensors"]["lidar"])
      throw io::InputError(manifest, "", "no sensors.lidar (the LiDAR mount): give --lidar-mount");
    T = io::decode_sim_config(rec.manifest["sensors"], manifest).lidar.T_base_lidar();
  }
  if (rec.cloud_count() == 0 && rec.scans.empty())
    throw io::InputError(a.in.string(), "", "recording has no LiDAR frames");
  // The one stack, as far as the detector: 3D sweeps are levelled by the recorded IMU's gravity
  // as on the robot (a cross slope otherwise biases the corridor centre towards uphill).
  navigate::NavStackConfig config;
  config.stack.mode = navigate::StackMode::detect;
  // A bag's motion (deskewing each sweep) comes from its nav_msgs/Odometry, not encoders.
  if (rec.encoders.empty() && !rec.odometry.empty())
    config.stack.odometry = navigate::OdometryInput::external;
  navigate::NavStackParts parts;
  parts.pipeline =
      std::make_unique<detect::DetectionPipeline>(io::make_pipeline(a.detector, a.config, T));
  navigate::NavStack stack(config, std::move(parts));
  std::int64_t frame = 0;
  io::replay_recording(rec, stack, {}, [&](const navigate::NavCommand& c) {
    emit(stack.pipeline(), c.frame->observation, frame++);
  });
}

void run(const DetectArgs& a) {
  // Both outputs are claimed first: a refused name is said before the work (io/safe_output.hpp).
  if (!a.svg.empty()) io::picture_format(a.svg);  // names the user's file, not the staging one
  io::OutputFile partial(a.out, a.overwrite);
  std::optional<io::OutputFile> picture;
  if (!a.svg.empty()) picture.emplace(a.svg, a.overwrite);
  std::ofstream out(partial.staging());
  if (!out) throw std::runtime_error(a.out.string() + ": cannot write");
  int index = 0;
  std::array<int, 3> by_status{};  // ok, degraded, no_rows
  std::vector<Eigen::Vector2f> svg_points;
  std::optional<core::RowObservation> svg_obs;
  const Emit emit = [&](const detect::DetectionPipeline& p, const core::RowObservation& obs,
                        std::optional<std::int64_t> frame) {
    out << observation_json(obs, frame).dump() << "\n";
    ++by_status[static_cast<std::size_t>(obs.status)];
    if (index++ == a.svg_frame) {
      svg_points = p.last_points();
      svg_obs = obs;
    }
  };
  const std::string ext = a.in.extension().string();
  if (fs::is_directory(a.in) || io::is_bag_file(a.in)) {
    run_recording(a, emit);  // its own pipeline: the mount comes from the manifest
  } else {
    const Eigen::Isometry3d T =
        a.mount.empty() ? Eigen::Isometry3d::Identity() : mount_transform(a.mount);
    auto p = io::make_pipeline(a.detector, a.config, T);
    if (ext == ".pcd" || ext == ".ply" || ext == ".PCD" || ext == ".PLY")
      emit(p, p.process(io::read_cloud(a.in)), std::nullopt);
    else if (ext == ".csv" && sniff_csv(a.in).scans)
      for (const auto& scan : io::read_scans_csv(a.in)) emit(p, p.process(scan), std::nullopt);
    else if (ext == ".csv")
      run_points_csv(a.in, p, emit);
    else
      throw io::InputError(
          a.in.string(), "",
          "unknown input type (expected .pcd, .ply, .csv, .mcap or a recording directory)");
  }
  out.close();
  if (!out) throw std::runtime_error(a.out.string() + ": cannot write");
  partial.commit();
  std::cout << a.detector << ": " << index << " frame(s) -> " << a.out.string() << " (ok "
            << by_status[0] << ", degraded " << by_status[1] << ", no_rows " << by_status[2]
            << ")\n";
  if (!a.svg.empty()) {
    if (!svg_obs)
      throw std::invalid_argument("--svg-frame " + std::to_string(a.svg_frame) +
                                  ": the input has " + std::to_string(index) + " frame(s)");
    write_detection_picture(picture->staging(), svg_points, *svg_obs,
                            a.detector + ", frame " + std::to_string(a.svg_frame) + ": " +
                                std::string(core::enum_name(svg_obs->status)));
    picture->commit();
  }
}

}  // namespace

void add_detect_command(CLI::App& app) {
  auto a = std::make_shared<DetectArgs>();
  CLI::App* c = app.add_subcommand(
      "detect",
      "Detect crop rows in LiDAR frames. Output: JSON lines, one object per frame: frame (when "
      "known), stamp [s], status (ok | degraded | no_rows), confidence [0-1], heading_deg, rows "
      "[{offset, heading_deg, x_min, x_max, support, rms}] sorted right to left, left / right "
      "{index, offset, heading_deg} (the nearest row on each side, or null), corridor {offset, "
      "heading_deg, width} or null. Base (robot) frame: x forward, y left, z up (REP 103); "
      "offsets are y at x = 0 in metres (left +), headings in degrees (counter-clockwise +). "
      "Input points are in the LiDAR frame, moved to the base frame by --lidar-mount.");
  std::string names;
  for (const auto& n : io::detector_names()) names += (names.empty() ? "" : ", ") + n;
  c->add_option("--detector", a->detector, "row detector: " + names)->required();
  c->add_option("--config", a->config,
                "detection config YAML (preprocess: + one section per detector), e.g. "
                "config/detect/vineyard.yaml; default: built-in defaults")
      ->check(CLI::ExistingFile);
  c->add_option("--in", a->in,
                "input: .pcd / .ply cloud; .csv of x,y[,z] points (a `frame` column: one output "
                "line per frame; x,y only: a planar sensor); .csv of scans (header " +
                    std::string(io::kScansCsvHeader) +
                    "); a recording directory (mount from its manifest's sensors.lidar); or a "
                    "ROS 2 bag .mcap (docs/bags.md)")
      ->required()
      ->check(CLI::ExistingPath);
  c->add_option("--out", a->out, "JSON-lines output file")->required();
  c->add_flag("--overwrite", a->overwrite, "replace existing --out / --svg files");
  c->add_option("--svg", a->svg,
                 "picture (.svg, .png or .pdf) of one frame: points and detected rows");
  c->add_option("--svg-frame", a->svg_frame, "0-based frame drawn by --svg (default 0)");
  c->add_option("--topics", a->topics,
                "bags: the topics read, e.g. cloud=/points,imu=/imu,odom=/odom,scan=/scan "
                "(default: the first topic of each message type)");
  c->add_option("--lidar-mount", a->mount,
                "T_base_lidar as x,y,z,roll_deg,pitch_deg,yaw_deg (metres, degrees; rotation "
                "Rz(yaw) Ry(pitch) Rx(roll)); default: identity, or the recording's mount")
      ->expected(6)
      ->delimiter(',');
  c->callback([a] { run(*a); });
}

}  // namespace rownav::app
