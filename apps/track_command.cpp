// `rownav track`: runs a row detector and a row tracker over a recording, frame by frame, with
// the odometry from one swappable source, and scores the deviations against the ground truth.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "setup.hpp"
#include "rownav/io/bag_recording.hpp"
#include "rownav/io/canvas.hpp"
#include "rownav/io/recording_replay.hpp"
#include "rownav/io/safe_output.hpp"
#include "rownav/navigate/nav_stack.hpp"
#include "rownav/core/angle.hpp"
#include "rownav/detect/pipeline.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav/io/localize_setup.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/localize/localizer.hpp"
#include "rownav/io/plot.hpp"
#include "rownav/io/recording.hpp"
#include "rownav/io/sim_setup.hpp"
#include "rownav/io/tracker_registry.hpp"

namespace rownav::app {

namespace {

namespace fs = std::filesystem;

struct TrackArgs {
  std::string detector, tracker;
  fs::path in, out, svg, detect_config, track_config, localize_config;
  std::string odometry = "localizer";
  std::string topics;         // bags: stream=/topic,...
  std::vector<double> mount;  // --lidar-mount, bags without a rownav manifest
  bool overwrite = false;
};

/// Index of the last sample at or before t in a stamp-sorted ground truth, -1 if none.
long before(const std::vector<sim::GroundTruth>& gt, double t) {
  const auto it = std::upper_bound(gt.begin(), gt.end(), t,
                                   [](double s, const sim::GroundTruth& g) { return s < g.stamp; });
  return static_cast<long>(it - gt.begin()) - 1;
}

/// True lateral / heading error at t when the robot is in a lane (nearest sample within 0.05 s).
std::optional<std::pair<double, double>> truth_at(const std::vector<sim::GroundTruth>& gt,
                                                  double t) {
  const long i = before(gt, t + 1e-9);
  for (const long k : {i, i + 1}) {
    if (k < 0 || static_cast<std::size_t>(k) >= gt.size()) continue;
    const auto& g = gt[std::size_t(k)];
    if (std::abs(g.stamp - t) <= 0.05 && g.place == sim::Place::lane)
      return std::make_pair(g.lateral_error, g.heading_error);
  }
  return std::nullopt;
}

struct Stats {
  std::array<int, 3> by_status{};  // tracking, coasting, lost
  double sq_lat = 0.0, sq_head = 0.0, max_lat = 0.0, max_head = 0.0;
  int scored = 0;
  io::Series est_lat{"lateral [cm]", {}, {}, io::Color::hex("#1f77b4")};
  io::Series true_lat{"true lateral [cm]", {}, {}, io::Color::hex("#1f77b4"), true};
  io::Series est_head{"heading [deg]", {}, {}, io::Color::hex("#d62728")};
  io::Series true_head{"true heading [deg]", {}, {}, io::Color::hex("#d62728"), true};
};

std::string cell(std::optional<double> v) {
  if (!v) return "";
  std::ostringstream s;
  s << *v;
  return s.str();
}

void record(const track::RowTracking& t, const std::vector<sim::GroundTruth>& gt, std::ostream& out,
            Stats& st) {
  ++st.by_status[static_cast<std::size_t>(t.status)];
  const bool valid = t.status != track::TrackStatus::lost;
  const auto truth = truth_at(gt, t.stamp);
  std::optional<double> lat, head, tl, th, el, eh;
  if (valid) lat = t.lateral_error, head = core::rad2deg(t.heading_error);
  if (truth) tl = truth->first, th = core::rad2deg(truth->second);
  if (valid && truth) {
    el = *lat - *tl, eh = *head - *th;
    st.sq_lat += *el * *el, st.sq_head += *eh * *eh, ++st.scored;
    st.max_lat = std::max(st.max_lat, std::abs(*el)),
    st.max_head = std::max(st.max_head, std::abs(*eh));
  }
  out << t.stamp << ',' << core::enum_name(t.status) << ',' << t.confidence << ',' << cell(lat)
      << ',' << cell(head) << ',' << (valid ? cell(t.row_spacing) : "") << ',' << cell(tl) << ','
      << cell(th) << ',' << cell(el) << ',' << cell(eh) << '\n';
  const double nan = std::nan("");
  for (auto* s : {&st.est_lat, &st.true_lat, &st.est_head, &st.true_head}) s->x.push_back(t.stamp);
  st.est_lat.y.push_back(lat ? 100.0 * *lat : nan);
  st.true_lat.y.push_back(tl ? 100.0 * *tl : nan);
  st.est_head.y.push_back(head.value_or(nan));
  st.true_head.y.push_back(th.value_or(nan));
}

/// The Localizer config: --localize-config, else the nominal one of the recording's robot
/// (manifest `robot` and `sensors`), else the defaults. `source` says which.
localize::LocalizerConfig localizer_config(const TrackArgs& a, const io::Recording& rec,
                                           std::string& source) {
  if (!a.localize_config.empty()) {
    source = a.localize_config.string();
    return io::load_localizer_config(a.localize_config);
  }
  const std::string manifest = (a.in / "manifest.yaml").string();
  if (rec.manifest["robot"] && rec.manifest["sensors"]) {
    sim::RobotConfig robot;
    io::decode_config(rec.manifest["robot"], robot, manifest);
    source = "nominal kinematics of the manifest's robot";
    return io::localizer_config_for(
        robot, io::decode_sim_config(rec.manifest["sensors"], manifest).encoders.ticks_per_rev);
  }
  source = "defaults (no robot in the manifest)";
  return {};
}

Eigen::Isometry3d recording_mount(const io::Recording& rec, const TrackArgs& a) {
  if (!a.mount.empty()) return mount_transform(a.mount);
  const bool bag = io::is_bag_file(a.in);
  const std::string manifest = bag ? a.in.string() : (a.in / "manifest.yaml").string();
  if (!rec.manifest["sensors"] || !rec.manifest["sensors"]["lidar"])
    throw io::InputError(manifest, "", bag ? "no rownav manifest (the LiDAR mount): give --lidar-mount"
                                           : "no sensors.lidar (the LiDAR mount)");
  return io::decode_sim_config(rec.manifest["sensors"], manifest).lidar.T_base_lidar();
}

/// A bag's odometry is its nav_msgs/Odometry, fed to the stack as an external odometry.
void check_bag(const TrackArgs& a, const io::Recording& rec) {
  if (a.odometry == "truth")
    throw io::InputError(a.in.string(), "", "--odometry truth: a bag has no ground truth");
  if (rec.odometry.empty())
    throw io::InputError(a.in.string(), "", "bag has no nav_msgs/msg/Odometry messages");
}

void run(const TrackArgs& a) {
  const bool bag = io::is_bag_file(a.in);
  if (!bag && !fs::is_directory(a.in))
    throw io::InputError(a.in.string(), "", "expected a recording directory or an .mcap bag");
  const io::Recording rec = bag ? io::read_bag_recording(a.in, io::parse_bag_topics(a.topics))
                                : io::read_recording(a.in);
  if (rec.cloud_count() == 0 && rec.scans.empty())
    throw io::InputError(a.in.string(), "", "recording has no LiDAR frames");
  if (bag) check_bag(a, rec);
  const bool truth = a.odometry == "truth";
  if (truth && rec.ground_truth.empty())
    throw io::InputError(a.in.string(), "", "--odometry truth: recording has no ground_truth.csv");
  if (!bag && !truth && rec.encoders.empty())
    throw io::InputError(a.in.string(), "", "recording has no encoders.csv (try --odometry truth)");
  // The one stack, run as far as the tracker, fed the recording as a robot would be.
  navigate::NavStackConfig config;
  config.stack.mode = navigate::StackMode::track;
  std::string source = bag ? "nav_msgs/Odometry of the bag" : "recorded ground truth";
  if (truth || bag)
    config.stack.odometry = navigate::OdometryInput::external;
  else
    config.localizer = localizer_config(a, rec, source);
  navigate::NavStackParts parts;
  parts.tracker = io::make_tracker(a.tracker, a.track_config);
  parts.pipeline = std::make_unique<detect::DetectionPipeline>(
      io::make_pipeline(a.detector, a.detect_config, recording_mount(rec, a)));
  navigate::NavStack stack(config, std::move(parts));
  std::cout << "odometry: " << (truth || bag ? source : "Localizer, " + source) << "\n";
  // Both outputs are claimed first: a refused name is said before the work (io/safe_output.hpp).
  if (!a.svg.empty()) io::picture_format(a.svg);  // names the user's file, not the staging one
  io::OutputFile partial(a.out, a.overwrite);
  std::optional<io::OutputFile> picture;
  if (!a.svg.empty()) picture.emplace(a.svg, a.overwrite);
  std::ofstream out(partial.staging());
  if (!out) throw std::runtime_error(a.out.string() + ": cannot write");
  out << "stamp,status,confidence,lateral,heading_deg,spacing,true_lateral,true_heading_deg,"
         "lateral_error,heading_error_deg\n";
  Stats st;
  int skipped = 0;
  io::ReplayOptions options;
  options.truth_odometry = truth;
  io::replay_recording(rec, stack, options, [&](const navigate::NavCommand& c) {
    if (!c.frame->tracking) return void(++skipped);  // no odometry at that stamp
    record(*c.frame->tracking, rec.ground_truth, out, st);
  });
  out.close();
  if (!out) throw std::runtime_error(a.out.string() + ": cannot write");
  partial.commit();
  if (!a.svg.empty()) {
    io::PlotOptions o;
    o.title = a.detector + " + " + a.tracker + ": deviations (dashed: truth)";
    o.x_label = "time [s]";
    o.y_label = "lateral [cm], heading [deg]";
    io::write_plot(picture->staging(), {st.est_lat, st.true_lat, st.est_head, st.true_head}, o);
    picture->commit();
  }
  const int frames = st.by_status[0] + st.by_status[1] + st.by_status[2];
  std::cout << a.tracker << " on " << a.detector << ": " << frames << " frame(s) -> "
            << a.out.string() << " (tracking " << st.by_status[0] << ", coasting "
            << st.by_status[1] << ", lost " << st.by_status[2];
  if (skipped > 0) std::cout << ", " << skipped << " without odometry";
  std::cout << ")";
  if (st.scored > 0) {
    std::cout << std::fixed << std::setprecision(2) << "; lateral RMSE "
              << 100.0 * std::sqrt(st.sq_lat / st.scored) << " cm, max " << 100.0 * st.max_lat
              << " cm; heading RMSE " << std::sqrt(st.sq_head / st.scored) << " deg, max "
              << st.max_head << " deg (" << st.scored << " frames in lanes)";
  }
  std::cout << "\n";
}

}  // namespace

void add_track_command(CLI::App& app) {
  auto a = std::make_shared<TrackArgs>();
  CLI::App* c = app.add_subcommand(
      "track",
      "Track crop rows over a recording: a row detector on every LiDAR frame, then a row tracker "
      "with the odometry of a wheel + IMU (+ GNSS) Localizer fed with the recording's samples "
      "(--odometry truth: its ground-truth poses); 3D sweeps are levelled with the "
      "accelerometer's gravity. Output CSV: stamp [s], "
      "status (tracking | coasting | lost), confidence [0-1], lateral [m] (offset of the robot "
      "from the corridor centre, left +), heading_deg (robot minus corridor), spacing [m], and "
      "from the ground truth (in lanes): true_lateral, true_heading_deg, lateral_error, "
      "heading_error_deg (estimate minus truth). Empty cells: unknown.");
  std::string detectors, trackers;
  for (const auto& n : io::detector_names()) detectors += (detectors.empty() ? "" : ", ") + n;
  for (const auto& n : io::tracker_names()) trackers += (trackers.empty() ? "" : ", ") + n;
  c->add_option("--in", a->in,
                "recording directory (rownav sim --out) or ROS 2 bag .mcap (docs/bags.md: its "
                "nav_msgs/Odometry is the odometry)")
      ->required()
      ->check(CLI::ExistingPath);
  c->add_option("--topics", a->topics,
                "bags: the topics read, e.g. cloud=/points,imu=/imu,odom=/odom,scan=/scan "
                "(default: the first topic of each message type)");
  c->add_option("--lidar-mount", a->mount,
                "T_base_lidar as x,y,z,roll_deg,pitch_deg,yaw_deg (default: the recording's "
                "manifest; required for a bag not written by rownav)")
      ->expected(6)
      ->delimiter(',');
  c->add_option("--detector", a->detector, "row detector: " + detectors)->required();
  c->add_option("--tracker", a->tracker, "row tracker: " + trackers)->required();
  c->add_option("--out", a->out, "CSV output file")->required();
  c->add_flag("--overwrite", a->overwrite, "replace existing --out / --svg files");
  c->add_option("--svg", a->svg, "plot (.svg, .png or .pdf) of the deviations over time");
  c->add_option("--detect-config", a->detect_config,
                "detection config YAML, e.g. config/detect/vineyard.yaml (default: built-in)")
      ->check(CLI::ExistingFile);
  c->add_option("--track-config", a->track_config,
                "tracking config YAML, e.g. config/track/default.yaml (default: built-in)")
      ->check(CLI::ExistingFile);
  c->add_option("--odometry", a->odometry,
                "odometry source: localizer (default: encoders + IMU + GNSS) or truth (the "
                "recorded true poses, for analysis)")
      ->check(CLI::IsMember({"localizer", "truth"}));
  c->add_option("--localize-config", a->localize_config,
                "Localizer config YAML (default: the nominal kinematics of the robot in the "
                "recording's manifest, else the built-in defaults)")
      ->check(CLI::ExistingFile);
  c->callback([a] { run(*a); });
}

}  // namespace rownav::app
