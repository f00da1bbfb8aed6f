// The closed loop: simulator samples -> navigate::NavStack -> command -> simulator.
#include "rownav/io/closed_loop_runner.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <optional>
#include <stdexcept>

#include "rownav/io/csv.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/io/nav_stack_setup.hpp"
#include "rownav/io/recording.hpp"
#include "rownav/io/recording_replay.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/vision/camera_labeller.hpp"
#include "rownav/vision/excess_green_detector.hpp"

namespace rownav::io {

namespace {

using Clock = std::chrono::steady_clock;

/// Distance from p to a convex polygon (0 inside).
double polygon_distance(const std::array<Eigen::Vector2d, 4>& poly, const Eigen::Vector2d& p) {
  bool inside = true;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const core::Segment2 s{poly[i], poly[(i + 1) % poly.size()]};
    best = std::min(best, s.distance(p));
    const Eigen::Vector2d e = s.b - s.a, d = p - s.a;
    if (e.x() * d.y() - e.y() * d.x() < 0.0) inside = false;  // corners are counter-clockwise
  }
  return inside ? 0.0 : best;
}

/// The order of a run's inputs, for io::replay_input_log (ClosedLoopSetup::record_inputs).
class InputLog {
 public:
  explicit InputLog(const std::filesystem::path& dir) : writer_(dir, YAML::Node()) {}
  void cloud(const core::PointCloud& c) { writer_.write_cloud(c), row("cloud", n_[0]++); }
  void scan(const core::Scan2D& s) { writer_.write_scan(s), row("scan", n_[1]++); }
  void encoders(const core::WheelEncoderSample& s) {
    writer_.write_encoders(s), row("encoders", n_[2]++);
  }
  void imu(const core::ImuSample& s) { writer_.write_imu(s), row("imu", n_[3]++); }
  void gnss(const core::GnssFix& s) { writer_.write_gnss(s), row("gnss", n_[4]++); }
  void command(const navigate::NavCommand& c) {
    log() << "command,0," << format_double(c.stamp) << ',' << format_double(c.cmd.v) << ','
          << format_double(c.cmd.omega) << ',' << core::enum_name(c.state) << '\n';
  }
  void commit() { writer_.commit(); }

 private:
  std::ostream& log() { return writer_.extra(kInputLog, "kind,index,stamp,v,omega,state"); }
  void row(const char* kind, std::size_t i) { log() << kind << ',' << i << ",0,0,0,\n"; }
  RecordingWriter writer_;
  std::array<std::size_t, 5> n_{};
};

/// Camera labels (issue 12): the simulated camera, the excess-green detector, the labeller.
struct CameraLabels {
  CameraLabels(const sim::PinholeCameraConfig& camera, int every, std::uint64_t seed)
      : camera(camera, seed), every(every) {}
  sim::PinholeCamera camera;
  vision::ExcessGreenDetector detector;
  vision::CameraLabeller labeller;
  int every = 1;
  int sweeps = 0;  // since the last image
};

/// Hands the simulator's samples to the stack (and the input log) and collects the metrics.
class RunnerSink : public sim::SimSink {
 public:
  RunnerSink(navigate::NavStack& stack, const sim::Simulator& sim, const ClosedLoopSetup& setup,
             RunResult& result, InputLog* log)
      : stack_(stack),
        sim_(sim),
        result_(result),
        log_(log),
        T_base_lidar_(setup.sensors.lidar.T_base_lidar().cast<float>()) {
    const sim::Field& field = *setup.field;
    if (setup.nav.place.enabled && setup.camera_labels)
      camera_.emplace(setup.camera, std::max(1, setup.camera_every),
                      setup.sensors.seed + kLabellerSeedOffset);
    else if (setup.nav.place.enabled && setup.truth_labels)
      labeller_.emplace(setup.labeller, setup.sensors.seed + kLabellerSeedOffset);
    for (const auto& p : field.plants)
      if (p.kind == sim::PlantKind::post || p.kind == sim::PlantKind::end_post) posts_.push_back(p);
  }
  void on_cloud(const core::PointCloud& c, const std::vector<sim::SurfaceClass>& classes) override {
    if (log_) log_->cloud(c);
    stack_.on_cloud(c, labels(c, classes));
  }
  void on_scan(const core::Scan2D& s, const std::vector<sim::SurfaceClass>&) override {
    if (log_) log_->scan(s);
    stack_.on_scan(s);
  }
  void on_encoders(const core::WheelEncoderSample& s) override {
    if (log_) log_->encoders(s);
    stack_.on_encoders(s);
  }
  void on_imu(const core::ImuSample& s) override {
    if (log_) log_->imu(s);
    stack_.on_imu(s);
  }
  void on_gnss(const core::GnssFix& s) override {
    if (log_) log_->gnss(s);
    stack_.on_gnss(s);
  }
  void on_ground_truth(const sim::GroundTruth& g) override {
    RunSample s;
    s.stamp = g.stamp;
    s.T_world_base = g.T_world_base;
    s.T_odom_base = stack_.T_odom_base(g.stamp).value_or(core::Pose2());
    s.place = g.place;
    s.corridor = g.corridor;
    s.planned_corridor = planned;
    s.state = state;
    s.lateral_error = g.lateral_error;
    s.heading_error = g.heading_error;
    s.twist = g.twist;
    s.cmd = cmd;
    s.plants_crushed = g.plants_crushed;
    record_crushes(g, s.state);
    const auto fp = sim_.robot().footprint_world();
    for (const auto& p : posts_)
      if ((p.position - g.T_world_base.translation()).norm() < 3.0 &&
          polygon_distance(fp, p.position) < p.radius)
        s.collision = true;
    s.obstacle_clearance = g.obstacle_clearance;
    if (g.obstacle_clearance <= 0.0) s.collision = true;  // touched the walking person
    result_.samples.push_back(s);
  }

  void record_crushes(const sim::GroundTruth& g, navigate::NavState st) {
    const auto& idx = sim_.crushed_plants();
    for (std::size_t k = result_.crushes.size(); k < idx.size(); ++k) {
      const auto& p = sim_.field().plants[static_cast<std::size_t>(idx[k])];
      result_.crushes.push_back({g.stamp, p.position, p.radius, st, g.T_world_base.translation()});
    }
  }

  /// Truth labels of a sweep's points (empty without a labeller: the stack's default).
  std::vector<map::PointLabel> labels(const core::PointCloud& c,
                                      const std::vector<sim::SurfaceClass>& classes) {
    std::vector<map::PointLabel> out;
    if (!labeller_ && !camera_) return out;
    points_base_.clear();
    for (const auto& p : c.points)
      points_base_.push_back(T_base_lidar_ * Eigen::Vector3f(p.x, p.y, p.z));
    if (camera_) {
      if (camera_->sweeps++ % camera_->every == 0)  // a new image: the first sweep, then every n
        camera_->labeller.set_image(  // the image at the robot's pose when the sweep arrives
            camera_->camera.render(sim_.world(), sim_.pose3d(sim_.robot_state().pose), c.stamp),
            camera_->detector);
      camera_->labeller.label(points_base_, out);
      return out;
    }
    labeller_->set_frame(sim_.robot_state().pose, classes);
    labeller_->label(points_base_, out);
    return out;
  }

  static constexpr std::uint64_t kLabellerSeedOffset = 7919;  // its own noise stream
  navigate::NavStack& stack_;
  const sim::Simulator& sim_;
  RunResult& result_;
  InputLog* log_;
  Eigen::Isometry3f T_base_lidar_;
  std::optional<sim::TruthLabeller> labeller_;
  std::optional<CameraLabels> camera_;
  std::vector<Eigen::Vector3f> points_base_;
  std::vector<sim::Plant> posts_;
  navigate::NavState state = navigate::NavState::in_row;
  int planned = -1;
  core::Twist2 cmd;
};

/// Tracker output vs ground truth for one frame.
FrameSample score_frame(const track::RowTracking& t, const sim::GroundTruth& g, bool in_row) {
  FrameSample f;
  f.stamp = t.stamp;
  f.in_row = in_row;
  f.status = t.status;
  f.lateral_error = t.lateral_error;
  f.heading_error = t.heading_error;
  f.true_lateral_error = g.lateral_error;
  f.true_heading_error = g.heading_error;
  f.row_spacing = t.row_spacing;
  auto compare = [&](int tracked, int truth_row) {
    if (tracked < 0 || tracked >= static_cast<int>(t.rows.size()) || truth_row < 0) return;
    for (const auto& r : g.rows)
      if (r.row == truth_row) {
        const auto& a = t.rows[static_cast<std::size_t>(tracked)].line_base;
        const auto& b = r.line_base;
        if (std::abs(a.direction.x()) < 1e-6 || std::abs(b.direction.x()) < 1e-6) return;
        f.slope_errors.push_back(a.direction.y() / a.direction.x() -
                                 b.direction.y() / b.direction.x());
        f.intercept_errors.push_back(a.y_at(0.0) - b.y_at(0.0));
      }
  };
  compare(t.left, g.left_row);
  compare(t.right, g.right_row);
  return f;
}

/// The mission's record of one command: events, entries (planned vs true corridor), row ends.
void record(navigate::NavCommand& out, const navigate::NavStack& stack, const sim::Simulator& sim,
            RunResult& result) {
  for (auto& e : out.events) {
    if (e.kind == navigate::NavEventKind::entered_corridor ||
        (e.kind == navigate::NavEventKind::safe_stop &&
         out.stop_reason == navigate::StopReason::place_contradicts_plan))
      result.entries.emplace_back(e.corridor, sim.ground_truth().corridor);
    result.events.push_back(std::move(e));
  }
  // Row ends estimated by the stack (odom frame), mapped into the world through the robot's
  // true pose at this instant: the error measured is that of the LiDAR estimate relative to
  // the robot (003 Table II), not the odometry drift accumulated since the start.
  const auto& ends = stack.navigator().row_ends_odom();
  const core::Pose2 T = stack.T_odom_base(sim.time()).value_or(core::Pose2());
  for (std::size_t k = result.row_ends_world.size(); k < ends.size(); ++k)
    result.row_ends_world.push_back(sim.robot_state().pose * (T.inverse() * ends[k]));
  for (const auto& p : out.row_end_points)  // 003 Table II: each turn frame's end points
    result.turn_row_ends_world.push_back({out.stamp, sim.robot_state().pose * (T.inverse() * p)});
  result.served = out.served;
  if (out.frame && out.frame->place)
    result.places.push_back({out.stamp, out.place, sim.ground_truth().place});
  for (const auto& k : out.key_locations)
    result.key_locations.push_back({k, sim.robot_state().pose * (T.inverse() * k.key.p)});
}

}  // namespace

core::Pose2 mission_start(const sim::FieldTruth& truth, const std::vector<int>& order, int block,
                          navigate::TurnSide first_turn, double lead_in) {
  const auto& c0 = truth.corridor_centre(block, order.front());
  core::check(c0.size() >= 2, "corridors",
              "corridor " + std::to_string(order.front()) + " does not exist in block " +
                  std::to_string(block));
  Eigen::Vector2d d = (c0[1] - c0[0]).normalized();
  bool forward = true;
  if (order.size() > 1) {
    const auto& c1 = truth.corridor_centre(block, order[1]);
    core::check(c1.size() >= 2, "corridors", "corridor " + std::to_string(order[1]) + " missing");
    const Eigen::Vector2d n(-d.y(), d.x());
    const bool next_left = n.dot(c1.front() - c0.front()) > 0.0;
    forward = next_left == (first_turn == navigate::TurnSide::left);
  }
  if (forward) {
    const Eigen::Vector2d p = c0.front() - lead_in * d;
    return {p.x(), p.y(), std::atan2(d.y(), d.x())};
  }
  const Eigen::Vector2d e = (c0[c0.size() - 2] - c0.back()).normalized();
  const Eigen::Vector2d p = c0.back() - lead_in * e;
  return {p.x(), p.y(), std::atan2(e.y(), e.x())};
}

core::Pose2 perturbed_start(const core::Pose2& start, double offset, double yaw) {
  return start * core::Pose2(0.0, offset, yaw);
}

std::unique_ptr<navigate::NavStack> make_nav_stack(const ClosedLoopSetup& setup,
                                                   const std::vector<int>& order) {
  navigate::NavStackConfig nav = setup.nav;
  nav_stack_robot(nav, setup.robot, setup.sensors.encoders.ticks_per_rev,
                  setup.sensors.lidar.rate_hz);
  navigate::NavStackParts parts;
  parts.pipeline = std::make_unique<detect::DetectionPipeline>(
      make_pipeline(setup.detector, setup.detect_config, setup.sensors.lidar.T_base_lidar()));
  parts.tracker = setup.make_tracker();
  parts.controller = setup.make_controller();
  return std::make_unique<navigate::NavStack>(nav, std::move(parts), order,
                                              setup.mission.first_turn);
}

RunResult run_closed_loop(const ClosedLoopSetup& setup) {
  core::check(setup.field != nullptr, "field", "missing");
  core::check(static_cast<bool>(setup.make_tracker), "tracker", "no tracker factory");
  core::check(static_cast<bool>(setup.make_controller), "controller", "no controller factory");
  const sim::FieldTruth truth(*setup.field);
  RunResult result;
  result.order = navigate::resolve_order(setup.mission, truth.corridor_count(setup.mission.block));
  const core::Pose2 start = perturbed_start(mission_start(truth, result.order, setup.mission.block,
                                                          setup.mission.first_turn, setup.lead_in),
                                            setup.start_offset, setup.start_yaw);
  result.T_world_odom = start;
  const auto stack_ptr = make_nav_stack(setup, result.order);
  navigate::NavStack& stack = *stack_ptr;

  sim::Simulator sim(*setup.field, setup.robot, setup.sensors, start);
  std::optional<InputLog> log;
  if (!setup.record_inputs.empty()) log.emplace(setup.record_inputs);
  RunnerSink sink(stack, sim, setup, result, log ? &*log : nullptr);
  const auto wall0 = Clock::now();
  core::Twist2 cmd;
  double next_progress = 0.0;
  while (true) {
    if (sim.time() >= setup.time_limit) {
      result.stop_reason = navigate::StopReason::timeout;
      break;
    }
    sim.step(cmd, sink);
    const bool was_in_row = stack.navigator().state() == navigate::NavState::in_row;
    navigate::NavCommand out = stack.command(sim.time());
    if (log) log->command(out);
    cmd = out.cmd;
    if (out.frame && out.frame->tracking) {
      FrameSample f = score_frame(*out.frame->tracking, sim.ground_truth(),
                                  was_in_row && sim.ground_truth().place == sim::Place::lane);
      f.latency = out.frame->latency;
      result.frames.push_back(std::move(f));
    }
    sink.state = out.state;
    sink.planned = out.corridor;
    sink.cmd = cmd;
    record(out, stack, sim, result);
    if (out.state == navigate::NavState::done || out.state == navigate::NavState::safe_stop) {
      result.stop_reason = out.stop_reason;
      break;
    }
    if (setup.progress && sim.time() >= next_progress) {
      next_progress = sim.time() + 1.0;
      setup.progress(sim.time(), static_cast<double>(out.served) / result.order.size());
    }
  }
  if (stack.navigator().state() == navigate::NavState::safe_stop) {
    sink.cmd = core::Twist2();
    for (const double end = sim.time() + setup.settle; sim.time() < end - 1e-9;)
      sim.step(sink.cmd, sink);
  }
  if (log) log->commit();
  result.final_state = stack.navigator().state();
  result.turns = stack.navigator().turns();
  result.odometry_alpha = stack.localizer().odometry_alpha();
  result.odometry_scale_samples = stack.odometry_scale().accepted();
  result.sim_time = sim.time();
  result.wall_time = std::chrono::duration<double>(Clock::now() - wall0).count();
  return result;
}

}  // namespace rownav::io
