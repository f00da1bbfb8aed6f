// The closed loop: simulator -> detection -> tracking -> end of row -> navigator -> robot.
#include "rownav/io/closed_loop_runner.hpp"

#include <chrono>
#include <cmath>
#include <deque>
#include <stdexcept>

#include "rownav/control/velocity_limits.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/io/localize_setup.hpp"
#include "rownav/localize/gravity_up.hpp"
#include "rownav/sim/field_truth.hpp"

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

/// Collects the simulator's output for the stack and the metrics.
class RunnerSink : public sim::SimSink {
 public:
  RunnerSink(OdometrySource& odom, const sim::Simulator& sim, const sim::Field& field,
             RunResult& result)
      : odom_(odom), sim_(sim), result_(result) {
    for (const auto& p : field.plants)
      if (p.kind == sim::PlantKind::post || p.kind == sim::PlantKind::end_post) posts_.push_back(p);
  }
  void on_cloud(const core::PointCloud& c, const std::vector<sim::SurfaceClass>&) override {
    cloud_ = c;
    has_cloud_ = true;
  }
  void on_scan(const core::Scan2D& s, const std::vector<sim::SurfaceClass>&) override {
    scan_ = s;
    has_scan_ = true;
  }
  void on_encoders(const core::WheelEncoderSample& s) override { odom_.on_encoders(s); }
  void on_imu(const core::ImuSample& s) override {
    odom_.on_imu(s);
    imu_.push_back(s);  // the last second, to level each sweep by gravity
    while (!imu_.empty() && imu_.front().stamp < s.stamp - 1.0) imu_.pop_front();
  }
  void on_gnss(const core::GnssFix& s) override { odom_.on_gnss(s); }
  void on_ground_truth(const sim::GroundTruth& g) override {
    RunSample s;
    s.stamp = g.stamp;
    s.T_world_base = g.T_world_base;
    s.T_odom_base = odom_.T_odom_base(g.stamp).value_or(core::Pose2());
    s.place = g.place;
    s.corridor = g.corridor;
    s.planned_corridor = planned;
    s.state = state;
    s.lateral_error = g.lateral_error;
    s.heading_error = g.heading_error;
    s.twist = g.twist;
    s.cmd = cmd;
    s.plants_crushed = g.plants_crushed;
    const auto fp = sim_.robot().footprint_world();
    for (const auto& p : posts_)
      if ((p.position - g.T_world_base.translation()).norm() < 3.0 &&
          polygon_distance(fp, p.position) < p.radius)
        s.collision = true;
    result_.samples.push_back(s);
  }

  OdometrySource& odom_;
  const sim::Simulator& sim_;
  RunResult& result_;
  std::vector<sim::Plant> posts_;
  core::PointCloud cloud_;
  core::Scan2D scan_;
  std::deque<core::ImuSample> imu_;
  bool has_cloud_ = false, has_scan_ = false;
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

/// One 3D sweep through the pipeline, levelled by the gravity the IMU measured during the sweep
/// when the set-up asks for it (a rolling base shifts the rows sideways by h sin(roll)).
core::RowObservation process_cloud(detect::DetectionPipeline& pipeline, const RunnerSink& sink,
                                   double speed, const ClosedLoopSetup& setup) {
  if (setup.level_by_gravity) {
    const std::vector<core::ImuSample> imu(sink.imu_.begin(), sink.imu_.end());
    const double t0 = sink.cloud_.stamp;
    const double t1 = t0 + 1.0 / setup.sensors.lidar.rate_hz;
    if (const auto up = localize::gravity_up(imu, t0, t1, speed))
      return pipeline.process(sink.cloud_, *up);
  }
  return pipeline.process(sink.cloud_);
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

RunResult run_closed_loop(const ClosedLoopSetup& setup) {
  core::check(setup.field != nullptr, "field", "missing");
  core::check(static_cast<bool>(setup.make_tracker), "tracker", "no tracker factory");
  core::check(static_cast<bool>(setup.make_controller), "controller", "no controller factory");
  const sim::FieldTruth truth(*setup.field);
  RunResult result;
  result.order = navigate::resolve_order(setup.mission, truth.corridor_count(setup.mission.block));
  const core::Pose2 start = mission_start(truth, result.order, setup.mission.block,
                                          setup.mission.first_turn, setup.lead_in);
  result.T_world_odom = start;
  auto pipeline =
      make_pipeline(setup.detector, setup.detect_config, setup.sensors.lidar.T_base_lidar());
  auto tracker = setup.make_tracker();
  auto controller = setup.make_controller();
  std::unique_ptr<OdometrySource> odom =
      setup.make_odometry
          ? setup.make_odometry()
          : std::make_unique<LocalizerOdometry>(localizer_config_for(setup.robot, setup.sensors));
  navigate::EndOfRowDetector eor(setup.end_of_row);
  navigate::Navigator nav(setup.navigator, result.order, setup.mission.first_turn, *tracker,
                          *controller, eor);
  navigate::RobotLimits limits;
  limits.width = setup.robot.width;
  limits.base_to_front = setup.robot.base_to_front;
  limits.turn = {setup.robot.can_turn_in_place(), setup.robot.min_turn_radius()};
  // The robot's limits are applied to every command, as a base controller would (the
  // controllers and manoeuvres do not clamp themselves).
  control::VelocityLimits vlim;
  vlim.max_speed = setup.robot.max_speed;
  vlim.max_reverse_speed = setup.robot.max_reverse_speed;
  vlim.max_yaw_rate = setup.robot.max_yaw_rate;
  vlim.max_accel = setup.robot.max_accel;
  vlim.max_yaw_accel = setup.robot.max_yaw_accel;
  vlim.min_turn_radius = setup.robot.min_turn_radius();

  sim::Simulator sim(*setup.field, setup.robot, setup.sensors, start);
  RunnerSink sink(*odom, sim, *setup.field, result);
  const auto wall0 = Clock::now();
  core::Twist2 cmd;
  double next_progress = 0.0;
  while (true) {
    if (sim.time() >= setup.time_limit) {
      result.stop_reason = navigate::StopReason::timeout;
      break;
    }
    sim.step(cmd, sink);
    odom->on_physics_step(sim.robot_state());
    const core::Pose2 T = odom->T_odom_base(sim.time()).value_or(core::Pose2());
    navigate::NavOutput out;
    if (sink.has_cloud_ || sink.has_scan_) {
      const auto t0 = Clock::now();
      const bool was_in_row = nav.state() == navigate::NavState::in_row;
      navigate::NavInput in;
      in.observation = sink.has_cloud_ ? process_cloud(pipeline, sink, odom->twist().v, setup)
                                       : pipeline.process(sink.scan_);
      sink.has_cloud_ = sink.has_scan_ = false;
      in.stamp = sim.time();
      in.T_odom_base = T;
      in.twist = odom->twist();
      // The frame is stamped at the start of the sweep: the tracker gets the pose of that instant.
      in.tracking =
          tracker->update(in.observation, odom->T_odom_base(in.observation.stamp).value_or(T));
      in.end_of_row = eor.update(pipeline.last_cloud_base(), pipeline.last_points(), in.tracking);
      in.points_base = pipeline.last_points();
      in.robot = limits;
      out = nav.step(in);
      FrameSample f = score_frame(in.tracking, sim.ground_truth(),
                                  was_in_row && sim.ground_truth().place == sim::Place::lane);
      f.latency = std::chrono::duration<double>(Clock::now() - t0).count();
      result.frames.push_back(std::move(f));
    } else {
      out = nav.hold(sim.time(), T);
    }
    cmd = control::apply_limits(out.cmd, cmd, sim.dt(), vlim);
    sink.state = out.state;
    sink.planned = out.corridor;
    sink.cmd = cmd;
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
    for (std::size_t k = result.row_ends_world.size(); k < nav.row_ends_odom().size(); ++k)
      result.row_ends_world.push_back(sim.robot_state().pose * (T.inverse() * nav.row_ends_odom()[k]));
    result.served = out.served;
    if (out.state == navigate::NavState::done || out.state == navigate::NavState::safe_stop) {
      result.stop_reason = out.stop_reason;
      break;
    }
    if (setup.progress && sim.time() >= next_progress) {
      next_progress = sim.time() + 1.0;
      setup.progress(sim.time(), static_cast<double>(out.served) / result.order.size());
    }
  }
  result.final_state = nav.state();
  result.turns = nav.turns();
  result.sim_time = sim.time();
  result.wall_time = std::chrono::duration<double>(Clock::now() - wall0).count();
  return result;
}

}  // namespace rownav::io
