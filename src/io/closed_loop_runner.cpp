// The closed loop: simulator samples -> navigate::NavStack -> command -> simulator.
#include "rownav/io/closed_loop_runner.hpp"

#include <chrono>
#include <cmath>
#include <deque>
#include <stdexcept>

#include "rownav/io/detector_registry.hpp"
#include "rownav/io/localize_setup.hpp"
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

/// Hands the simulator's samples to the stack and collects the metrics.
class RunnerSink : public sim::SimSink {
 public:
  RunnerSink(navigate::NavStack& stack, const sim::Simulator& sim, const sim::Field& field,
             RunResult& result)
      : stack_(stack), sim_(sim), result_(result) {
    for (const auto& p : field.plants)
      if (p.kind == sim::PlantKind::post || p.kind == sim::PlantKind::end_post) posts_.push_back(p);
  }
  void on_cloud(const core::PointCloud& c, const std::vector<sim::SurfaceClass>&) override {
    stack_.on_cloud(c);
  }
  void on_scan(const core::Scan2D& s, const std::vector<sim::SurfaceClass>&) override {
    stack_.on_scan(s);
  }
  void on_encoders(const core::WheelEncoderSample& s) override { stack_.on_encoders(s); }
  void on_imu(const core::ImuSample& s) override { stack_.on_imu(s); }
  void on_gnss(const core::GnssFix& s) override { stack_.on_gnss(s); }
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
    const auto fp = sim_.robot().footprint_world();
    for (const auto& p : posts_)
      if ((p.position - g.T_world_base.translation()).norm() < 3.0 &&
          polygon_distance(fp, p.position) < p.radius)
        s.collision = true;
    s.obstacle_clearance = g.obstacle_clearance;
    if (g.obstacle_clearance <= 0.0) s.collision = true;  // touched the walking person
    result_.samples.push_back(s);
  }

  navigate::NavStack& stack_;
  const sim::Simulator& sim_;
  RunResult& result_;
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
  result.served = out.served;
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

void nav_stack_robot(navigate::NavStackConfig& nav, const sim::RobotConfig& robot,
                     const sim::SimConfig& sensors) {
  nav.robot.width = robot.width;
  nav.robot.base_to_front = robot.base_to_front;
  nav.robot.turn = {robot.can_turn_in_place(), robot.min_turn_radius()};
  // The robot's limits are applied to every command, as a base controller would (the
  // controllers and manoeuvres do not clamp themselves).
  nav.limits.max_speed = robot.max_speed;
  nav.limits.max_reverse_speed = robot.max_reverse_speed;
  nav.limits.max_yaw_rate = robot.max_yaw_rate;
  nav.limits.max_accel = robot.max_accel;
  nav.limits.max_yaw_accel = robot.max_yaw_accel;
  nav.limits.min_turn_radius = robot.min_turn_radius();
  nav.localizer = localizer_config_for(robot, sensors);
  nav.stack.sweep_period = 1.0 / sensors.lidar.rate_hz;
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
  navigate::NavStackConfig nav = setup.nav;
  nav_stack_robot(nav, setup.robot, setup.sensors);
  navigate::NavStackParts parts;
  parts.pipeline = std::make_unique<detect::DetectionPipeline>(
      make_pipeline(setup.detector, setup.detect_config, setup.sensors.lidar.T_base_lidar()));
  parts.tracker = setup.make_tracker();
  parts.controller = setup.make_controller();
  navigate::NavStack stack(nav, std::move(parts), result.order, setup.mission.first_turn);

  sim::Simulator sim(*setup.field, setup.robot, setup.sensors, start);
  RunnerSink sink(stack, sim, *setup.field, result);
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
  result.final_state = stack.navigator().state();
  result.turns = stack.navigator().turns();
  result.sim_time = sim.time();
  result.wall_time = std::chrono::duration<double>(Clock::now() - wall0).count();
  return result;
}

}  // namespace rownav::io
