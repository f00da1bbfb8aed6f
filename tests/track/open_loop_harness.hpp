#pragma once
// Open-loop tracking scenarios: the scripted pure-pursuit driver drives the simulator along one
// vineyard corridor; each LiDAR sweep then goes through a detection pipeline (levelled with the
// accelerometer's gravity, localize/gravity_up.hpp) and a tracker, with the odometry from a
// pluggable source: the wheel + IMU Localizer with the robot's NOMINAL kinematics (default), or
// the ground-truth poses with an optional synthetic drift. RowTracking is compared with the
// GroundTruth (lateral / heading error, left +, robot minus corridor). The simulation is run once
// per scenario; detector x tracker pairs replay it.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rownav/core/angle.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/navigate/nav_stack.hpp"
#include "rownav/io/localize_setup.hpp"
#include "rownav/localize/localizer.hpp"
#include "rownav/io/tracker_registry.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/scripted_path.hpp"
#include "rownav/sim/simulator.hpp"
#include "rownav/track/row_tracker.hpp"

namespace rownav::test {

/// Where the tracker's odometry comes from.
enum class OdometryKind { localizer, truth };

/// One open-loop scenario.
struct OpenLoopScenario {
  std::string name = "straight";
  double row_length = 10.0;            // [m]
  double curvature_amplitude = 0;      // [m] sine bend of the rows
  double curvature_wavelength = 40.0;  // [m]
  int gap_count = 0;                   // gaps of gap_length consecutive missing vines (random rows)
  int gap_length = 3;                  // [-]
  sim::WeedLevel weeds = sim::WeedLevel::none;
  double slip_noise = 0.02;  // [-] robot track slip (RobotConfig::slip_noise)
  OdometryKind odometry = OdometryKind::localizer;
  bool level = true;                // level each sweep with the accelerometer's gravity
  double odom_scale_error = 0.0;    // [-] truth odometry only: distance scale error (drift)
  double odom_yaw_drift_deg = 0.0;  // [deg/s] truth odometry only: yaw drift
  double blackout_start = -1.0;     // [s] detector replaced by no_rows in [start, start + length)
  double blackout_length = 0.0;     // [s]
  std::uint64_t seed = 3;
};

/// What the simulation produced: sweeps, proprioception and ground truth.
struct OpenLoopRecording {
  std::vector<core::PointCloud> clouds;
  std::vector<core::WheelEncoderSample> encoders;
  std::vector<core::ImuSample> imu;
  std::vector<sim::GroundTruth> truth;
  Eigen::Isometry3d T_base_lidar = Eigen::Isometry3d::Identity();
  localize::LocalizerConfig localizer;  // nominal kinematics (io::localizer_config_for)
  double sweep_period = 0.1;            // [s] a sweep is stamped at its start, complete 1 period later
};

struct Capture : sim::SimSink {
  OpenLoopRecording* rec = nullptr;
  void on_cloud(const core::PointCloud& c, const std::vector<sim::SurfaceClass>&) override {
    rec->clouds.push_back(c);
  }
  void on_encoders(const core::WheelEncoderSample& e) override { rec->encoders.push_back(e); }
  void on_imu(const core::ImuSample& i) override { rec->imu.push_back(i); }
  void on_ground_truth(const sim::GroundTruth& g) override { rec->truth.push_back(g); }
};

inline sim::FieldConfig open_loop_field(const OpenLoopScenario& s) {
  sim::FieldConfig c;
  c.kind = sim::FieldKind::vineyard;
  c.vineyard.rows = 4;
  c.vineyard.row_length = s.row_length;
  c.vineyard.row_spacing = 2.0;
  c.vineyard.headland_width = 4.0;
  c.vineyard.gap_count = s.gap_count;
  c.vineyard.gap_length_plants = s.gap_length;
  c.vineyard.weeds = s.weeds;
  c.vineyard.curvature_amplitude = s.curvature_amplitude;
  c.vineyard.curvature_wavelength = s.curvature_wavelength;
  c.terrain.roughness = 0.02;
  c.seed = s.seed;
  return c;
}

/// Drives corridor 1 (between rows 1 and 2) at 1 m/s with an OS1-16.
inline OpenLoopRecording simulate(const OpenLoopScenario& s) {
  const sim::Field field = sim::generate_field(open_loop_field(s));
  sim::RobotConfig robot;
  robot.slip_noise = s.slip_noise;
  sim::SimConfig config;
  config.seed = s.seed;
  sim::PathConfig path;
  path.corridors = {1};
  path.lead_in = 1.0;
  path.lead_out = 0.5;
  const auto points = sim::build_path(sim::FieldTruth(field), path, robot);
  const Eigen::Vector2d d = points[1].p - points[0].p;
  const core::Pose2 start(points[0].p.x(), points[0].p.y(), std::atan2(d.y(), d.x()));
  sim::Simulator simulator(field, robot, config, start);
  sim::PathFollower driver(points);
  OpenLoopRecording rec;
  rec.T_base_lidar = config.lidar.T_base_lidar();
  rec.localizer = io::localizer_config_for(robot, config.encoders.ticks_per_rev);
  rec.sweep_period = 1.0 / config.lidar.rate_hz;
  Capture capture;
  capture.rec = &rec;
  while (!driver.done() && simulator.time() < 3.0 * s.row_length + 10.0)
    simulator.step(driver.command(simulator.robot_state().pose), capture);
  return rec;
}

/// Ground-truth poses with an optional drift, as an external odometry: every increment's
/// translation is scaled by (1 + scale_error) and its rotation grows by yaw_drift * dt.
inline std::vector<localize::StampedPose> drifted_truth(const std::vector<sim::GroundTruth>& gt,
                                                        double scale_error,
                                                        double yaw_drift_rad_s) {
  std::vector<localize::StampedPose> odom;
  core::Pose2 T;
  for (std::size_t i = 0; i < gt.size(); ++i) {
    if (i == 0) {
      T = gt[0].T_world_base;
    } else {
      core::Pose2 step = gt[i - 1].T_world_base.inverse() * gt[i].T_world_base;
      step = {step.x * (1 + scale_error), step.y * (1 + scale_error),
              step.theta + yaw_drift_rad_s * (gt[i].stamp - gt[i - 1].stamp)};
      T = T * step;
    }
    odom.push_back({gt[i].stamp, T, gt[i].twist});
  }
  return odom;
}

/// Feeds a NavStack the recorded samples in time order up to a time: a sweep stamped at t is
/// complete (emitted) at t + sweep_period, when a live robot has every sample up to then.
class SampleFeed {
 public:
  SampleFeed(const OpenLoopRecording& rec, std::vector<localize::StampedPose> odometry)
      : rec_(rec), odom_(std::move(odometry)) {}
  void feed_until(navigate::NavStack& stack, double t) {
    constexpr double never = std::numeric_limits<double>::infinity();
    for (;;) {
      // Encoders only without an external odometry (the stack's own Localizer).
      const double te = odom_.empty() && ie_ < rec_.encoders.size() ? rec_.encoders[ie_].stamp : never;
      const double ti = ii_ < rec_.imu.size() ? rec_.imu[ii_].stamp : never;
      const double to = io_ < odom_.size() ? odom_[io_].stamp : never;
      const double next = std::min({te, ti, to});
      if (!(next <= t)) return;
      if (te == next)
        stack.on_encoders(rec_.encoders[ie_++]);
      else if (ti == next)
        stack.on_imu(rec_.imu[ii_++]);
      else
        stack.on_odometry(odom_[io_++]);
    }
  }

 private:
  const OpenLoopRecording& rec_;
  std::vector<localize::StampedPose> odom_;
  std::size_t ie_ = 0, ii_ = 0, io_ = 0;
};

/// Scores of one detector x tracker run over a scenario (in-lane frames only).
struct OpenLoopScore {
  int frames = 0, lane_frames = 0, scored = 0, lost_in_lane = 0, coasting = 0;
  double lat_mean = 0, lat_rmse = 0, lat_max = 0, head_rmse_deg = 0, head_max_deg = 0;
  std::vector<track::TrackStatus> status;  // per frame
  std::vector<double> stamps;              // per frame
};

inline const sim::GroundTruth* truth_at(const std::vector<sim::GroundTruth>& gt, double t) {
  const auto it = std::lower_bound(gt.begin(), gt.end(), t - 0.026,
                                   [](const sim::GroundTruth& g, double s) { return g.stamp < s; });
  return it != gt.end() && std::abs(it->stamp - t) <= 0.026 ? &*it : nullptr;
}

/// Replays a recording through navigate::NavStack (as far as the tracker) with detector
/// `detector` and tracker `tracker` ("none": the raw detector corridor).
inline OpenLoopScore run_open_loop(const OpenLoopRecording& rec, const OpenLoopScenario& s,
                                   const std::string& detector, const std::string& tracker) {
  navigate::NavStackConfig config;
  config.stack.mode = navigate::StackMode::track;
  config.stack.level_by_gravity = s.level;
  config.stack.sweep_period = rec.sweep_period;
  config.localizer = rec.localizer;
  const bool truth = s.odometry == OdometryKind::truth;
  if (truth) config.stack.odometry = navigate::OdometryInput::external;
  navigate::NavStackParts parts;
  parts.pipeline = std::make_unique<detect::DetectionPipeline>(io::make_pipeline(
      detector, std::string(ROWNAV_SOURCE_DIR) + "/config/detect/vineyard.yaml", rec.T_base_lidar));
  // "none" is the registry's raw-corridor tracker (track/raw_corridor.hpp).
  parts.tracker = io::make_tracker(tracker, {});
  navigate::NavStack stack(config, std::move(parts));
  SampleFeed feed(rec, truth ? drifted_truth(rec.truth, s.odom_scale_error,
                                             core::deg2rad(s.odom_yaw_drift_deg))
                             : std::vector<localize::StampedPose>{});
  OpenLoopScore sc;
  double sq_lat = 0, sq_head = 0;
  const double t0 = rec.truth.front().stamp;
  for (const auto& cloud : rec.clouds) {
    const double t = cloud.stamp, t_end = t + rec.sweep_period;
    feed.feed_until(stack, t_end);
    if (t - t0 >= s.blackout_start && t - t0 < s.blackout_start + s.blackout_length) {
      core::PointCloud blind;  // artificial blackout: the LiDAR returns nothing
      blind.stamp = t;
      stack.on_cloud(blind);
    } else {
      stack.on_cloud(cloud);
    }
    const navigate::NavCommand c = stack.command(t_end);
    if (!c.frame || !c.frame->tracking) continue;  // no odometry at the frame
    const track::RowTracking& out = *c.frame->tracking;
    ++sc.frames;
    sc.status.push_back(out.status);
    sc.stamps.push_back(t);
    const sim::GroundTruth* g = truth_at(rec.truth, t);
    if (!g || g->place != sim::Place::lane) continue;
    ++sc.lane_frames;
    if (out.status == track::TrackStatus::lost) {
      ++sc.lost_in_lane;
      continue;
    }
    if (out.status == track::TrackStatus::coasting) ++sc.coasting;
    const double el = out.lateral_error - g->lateral_error;
    const double eh = core::rad2deg(core::angle_diff(out.heading_error, g->heading_error));
    sq_lat += el * el, sq_head += eh * eh, sc.lat_mean += el, ++sc.scored;
    sc.lat_max = std::max(sc.lat_max, std::abs(el));
    sc.head_max_deg = std::max(sc.head_max_deg, std::abs(eh));
  }
  if (sc.scored > 0) {
    sc.lat_rmse = std::sqrt(sq_lat / sc.scored);
    sc.lat_mean /= sc.scored;
    sc.head_rmse_deg = std::sqrt(sq_head / sc.scored);
  }
  return sc;
}

/// The scenario set of the issue: straight, gently curved, missing vines, weeds, slip; all with
/// the Localizer odometry but truth_drift (ground truth with a synthetic drift).
inline std::vector<OpenLoopScenario> open_loop_scenarios() {
  std::vector<OpenLoopScenario> v;
  OpenLoopScenario s;
  v.push_back(s);
  s.name = "curved", s.curvature_amplitude = 0.3;
  v.push_back(s);
  s = {}, s.name = "gaps_3", s.gap_count = 6, s.gap_length = 3;
  v.push_back(s);
  s = {}, s.name = "gaps_5", s.gap_count = 6, s.gap_length = 5;
  v.push_back(s);
  s = {}, s.name = "weeds_some", s.weeds = sim::WeedLevel::some;
  v.push_back(s);
  s = {}, s.name = "weeds_many", s.weeds = sim::WeedLevel::many;
  v.push_back(s);
  // Heavy track slip: the Localizer's nominal kinematics drift (x_icr, alpha unknown).
  s = {}, s.name = "slip_drift", s.slip_noise = 0.1;
  v.push_back(s);
  // Ground-truth odometry with a synthetic drift: a known, larger odometry error.
  s = {}, s.name = "truth_drift", s.odometry = OdometryKind::truth, s.odom_scale_error = 0.03,
  s.odom_yaw_drift_deg = 0.5;
  v.push_back(s);
  return v;
}

}  // namespace rownav::test
