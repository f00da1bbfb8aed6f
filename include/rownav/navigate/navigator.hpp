#pragma once
/// @file navigator.hpp The mission state machine: in_row -> exiting -> turning -> headland ->
/// entering -> in_row ... -> done, or safe_stop with a reason (Bertoglio 2023,
/// 003_25dc0df51a1e5faf.txt sec. II: in-row, turn and end-row navigation).
///
/// The navigator owns no perception and no controller: navigate::NavStack runs the detector, the
/// tracker and the end-of-row detector each LiDAR frame and passes their answers with the
/// odometry pose; in a row the navigator answers with a control request that the stack's
/// controller turns into the command, and it asks the stack to reset the perception on a turn.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <deque>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/control/controller.hpp"
#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/core/row_observation.hpp"
#include "rownav/core/twist.hpp"
#include "rownav/navigate/end_of_row.hpp"
#include "rownav/navigate/headland_manoeuvre.hpp"
#include "rownav/navigate/mission_plan.hpp"
#include "rownav/navigate/place_gate.hpp"
#include "rownav/navigate/row_end_estimator.hpp"
#include "rownav/navigate/row_end_poles.hpp"
#include "rownav/track/row_tracker.hpp"

namespace rownav::navigate {

/// State of the mission.
enum class NavState : std::uint8_t {
  in_row,
  exiting,
  turning,
  headland,
  entering,
  done,
  safe_stop
};
/// Why the run stopped (summary.json `stop_reason`).
enum class StopReason : std::uint8_t {
  none,
  done,
  perception_lost,
  obstacle,
  place_contradicts_plan,
  timeout,
  budget_exceeded,       ///< a state took far longer / farther than planned (NavStack's watchdog)
  odometry_implausible,  ///< commanded motion the odometry did not see (NavStack's watchdog)
  /// resumed after the robot was carried out of the tracked rows or into another corridor
  /// during a hold (NavStack::resume_blocker, issue 15)
  moved_while_held
};
/// Something that happened (events timeline of the report).
enum class NavEventKind : std::uint8_t {
  row_end,
  exit_done,
  turn_started,
  row_passed,
  reanchored,
  turn_finished,
  entered_corridor,
  safe_stop,
  mission_done,
  input_stale,    ///< the watchdog zeroes the command: LiDAR or odometry too old
  input_resumed,  ///< fresh inputs again: the command is released
  /// the lane between the followed rows' canopies is narrower than the robot: it will brush
  /// or crush plants however well it steers (once per corridor; issue 11)
  narrow_corridor,
  /// exiting: the followed rows go on beyond the declared row end; back in the row (issue 10)
  row_end_withdrawn,
  /// held (paused, or not started): the tracked rows say the robot moved (pushed, carried) or
  /// are lost; once per hold, so an operator checks the robot before resuming (issue 15)
  moved_while_held
};

/// One event.
struct NavEvent {
  double stamp = 0.0;  ///< [s]
  NavEventKind kind = NavEventKind::row_end;
  int corridor = -1;                                ///< corridor concerned (plan index)
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< [m] odom, when relevant
  std::string text;                                 ///< one line for people
};

/// Geometry and limits of the robot the navigator needs.
struct RobotLimits {
  double width = 0.6;           ///< [m] footprint width
  double length = 0.9;          ///< [m] footprint length (the swept circle of a rotation)
  double base_to_front = 0.45;  ///< [m] base to the front of the footprint
  TurnAbility turn;             ///< in-place turns / min radius
};

/// Navigator parameters.
struct NavigatorConfig {
  double row_speed = 0.8;      ///< [m/s] in rows (003 sec. III: up to 1 m/s in the real vineyard)
  double entry_speed = 0.4;    ///< [m/s] entering a corridor after a turn
  double exit_distance = 1.2;  ///< [m] beyond the row ends, by odometry, before turning (003 II-B)
  /// [m] the exit also reaches the followed rows' measured canopy half width (a tree crown's
  /// radius past its last trunk) plus half the robot's width plus this clearance, so the turn
  /// and the headland leg pass the row ends clear of the crowns (issue 10; vines: 0.25 m half
  /// widths keep exit_distance)
  double exit_clearance = 0.5;
  double perception_timeout = 0.5;  ///< [s] in a row without rows seen -> safe stop
  /// [m] ...unless the row ends this close ahead by the settled row-end estimate
  /// (row_end_estimate.settle_*): then the rows ran out, the robot leaves the row as at a
  /// detected end. A planar detector loses rows shorter than ~3.5 m (PEARL on an LMS1xx in
  /// quick_vineyard); the end-of-row box's far edge (5 m) bounds it. Not when the lane ahead is
  /// hidden (end-of-row shadow test) or a followed row's returns go on past that end for
  /// row_end_estimate.settle_distance (issue 11, rownav)
  double lost_rows_end_reach = 5.0;
  /// Exiting: both followed rows still tracked from beside the robot, their end (the row-end
  /// estimate) more than end_withdraw_reach past the declared one, and this frame's returns along
  /// a followed row filling more than row_end_estimate.settle_distance of it past that end (in
  /// bins of settle_tolerance, within settle_tolerance of the row's line: not a few returns of
  /// one ring on a bump; zoo:1:11): withdraw it (back in the row, the end-of-row detector
  /// re-armed). A gap between trees, a blind frame (a small robot pitching on a bump) or a
  /// short-sighted moment ended the rows; rows that go on beyond the end say so. Off, the exit
  /// followed the end ahead until its time budget ran out (issue 10: 5 of the zoo's orchards
  /// stopped `budget_exceeded` in `exiting`; rownav). 3D sweeps only: a planar scan's rows run on
  /// past a real row end along whatever stands in its plane beyond it (zoo:7:5 on an
  /// LMS1xx: 3.4-5.2 m past both row ends; the end of row has its own shadow and blindness tests
  /// for planar scans)
  bool withdraw_end = true;
  /// [m] see withdraw_end. 0: the end-of-row detector's extent_distance, the reach within which
  /// the followed rows' ends declare a row end (the Navigator's `end_of_row`). Also how far the
  /// row end may move past the declared one while exiting without being withdrawn: the exit ends
  /// exit distance past the nearer of the two (zoo:1:11: row models stretched by a few returns
  /// in an uphill headland pushed the exit on until its budget ran out) (rownav)
  double end_withdraw_reach = 0.0;
  /// [m] a mission starts in the headland before its first corridor: the end of row is armed
  /// only once a followed row's support begins within this distance ahead of the base (the robot
  /// is at the rows). Before that, the empty ground between the robot and the row start reads as
  /// a row end (issue 11: a 4 m 2D scanner and a short bed exited before the bed, 3/3 runs)
  double arm_reach = 1.0;
  /// [frames] tracked frames in a row whose lane between the followed rows' canopies (centre
  /// lines and half widths; a planar scan's fitted faces) is narrower than the robot before the
  /// narrow_corridor event (rownav; issue 11: 0.6 m cabbage rows leave 0.35 m for a 0.32 m robot).
  /// 0 = off, the default: vine and tree canopies overhang the robot (the 1.8 m vineyard's
  /// crowns leave 0.49 m for a 0.6 m robot that crushes nothing); config/navigate/row_crop.yaml
  /// and market_garden.yaml turn it on (plants from the ground up)
  int narrow_frames = 0;
  /// [m] per side: the lane counts as narrow below the robot's width plus twice this (what a
  /// row follower's lateral error and the plants' size spread take; rownav: mean displacement
  /// 0.01-0.03 m in BENCHMARK.md, heads 15 % larger than their mean)
  double narrow_margin = 0.05;
  double stop_distance = 0.5;  ///< [m] obstacle this close to the footprint front -> safe stop
  /// [m] while a turn rotates the robot in place, an obstacle is a point within the circle its
  /// footprint sweeps (the farthest corner from base_link) plus this: a rotation moves no point
  /// of the robot forward, so the stop box ahead of the front stopped turns on the row ends the
  /// robot was only turning beside (issue 10: 4 of the zoo's obstacle stops) (rownav)
  double rotation_clearance = 0.1;
  int obstacle_min_points = 10;  ///< [points] in the stop box that make an obstacle
  /// [s] in a row, something in the controllers' front rectangle (which slows them down from
  /// fewer points than the stop box needs) holding the robot below blocked_speed this long ->
  /// safe stop `obstacle`: a robot that waits for ever for a weed to move is stalled, not safe
  /// (issue 13; a 2D vineyard run with many weeds sat 1,770 s in front of one) (rownav)
  double blocked_timeout = 10.0;
  double blocked_speed = 0.05;     ///< [m/s] below this the robot counts as held (rownav)
  double entry_check_depth = 1.5;  ///< [m] into the target corridor before checking the place
  double entry_max_depth = 6.0;    ///< [m] entering without a corridor seen -> perception_lost
  RowEndEstimatorConfig row_end_estimate;  ///< row ends and spacing of the corridor being left
  double entry_gate = 0.5;  ///< [-] x spacing: observed vs planned corridor centre, right place
  /// [deg] ...and the observed corridor's heading within this of the planned entry line's: a
  /// tracked centre line is a corridor only along it. The offset alone, taken at the robot,
  /// passed a line 22-30 deg across the rows (the tracker still settling after the rotation),
  /// which the entry then steered on into a row end (issue 10: zoo:1:36, an obstacle stop at
  /// the end post). Curved fields' rows turn a few degrees between neighbouring corridors' ends.
  /// Cost: where the entry line itself is off (an exit that followed the tracker swinging at the
  /// row ends: config/fields/maize.yaml, 21 deg), the true rows are refused (rownav)
  double entry_heading_gate_deg = 15.0;
  double line_gain = 1.5;     ///< [1/m] lateral gain of the odometry line follower (exit / entry)
  double heading_gain = 1.5;  ///< [1/s] heading gain of the same
  ManoeuvreChoice manoeuvre = ManoeuvreChoice::automatic;  ///< headland turn
  ManoeuvreConfig turn;                                    ///< manoeuvre parameters
  RowEndConfig row_ends;  ///< row-end estimator in the headland (003 sec. II-C)
  /// the map stage's validated place on the exit and the entry (Emmi 2021 Table 1; issue 12)
  PlaceGateConfig place_gate;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("row_speed", s.row_speed);
    v("entry_speed", s.entry_speed);
    v("exit_distance", s.exit_distance);
    v("exit_clearance", s.exit_clearance);
    v("perception_timeout", s.perception_timeout);
    v("lost_rows_end_reach", s.lost_rows_end_reach);
    v("withdraw_end", s.withdraw_end);
    v("end_withdraw_reach", s.end_withdraw_reach);
    v("arm_reach", s.arm_reach);
    v("narrow_frames", s.narrow_frames);
    v("narrow_margin", s.narrow_margin);
    v("stop_distance", s.stop_distance);
    v("rotation_clearance", s.rotation_clearance);
    v("obstacle_min_points", s.obstacle_min_points);
    v("blocked_timeout", s.blocked_timeout);
    v("blocked_speed", s.blocked_speed);
    v("entry_check_depth", s.entry_check_depth);
    v("entry_max_depth", s.entry_max_depth);
    v("row_end_estimate", s.row_end_estimate);
    v("entry_gate", s.entry_gate);
    v("entry_heading_gate_deg", s.entry_heading_gate_deg);
    v("line_gain", s.line_gain);
    v("heading_gain", s.heading_gain);
    v("manoeuvre", s.manoeuvre);
    v("turn", s.turn);
    v("row_ends", s.row_ends);
    v("place_gate", s.place_gate);
  }
  void validate() const;
};

/// What the navigator sees each LiDAR frame.
struct NavInput {
  double stamp = 0.0;                            ///< [s]
  core::Pose2 T_odom_base;                       ///< odometry pose at stamp
  core::Twist2 twist;                            ///< body velocity estimate
  core::RowObservation observation;              ///< detector output
  track::RowTracking tracking;                   ///< tracker output
  EndOfRowResult end_of_row;                     ///< end-of-row detector output
  std::span<const Eigen::Vector2f> points_base;  ///< 2D points, base frame (row ends, obstacles)
  bool sweep_3d = false;  ///< the frame was a 3D sweep (false: a planar scan)
  /// Obstacle candidates by height (3D sweeps, navigate/obstacle_points.hpp); when set, the
  /// obstacle stop counts these instead of points_base
  std::optional<std::span<const Eigen::Vector2f>> obstacle_points_base;
  RobotLimits robot;
  /// [m] to the nearest obstacle in the controllers' front rectangle (StackConfig::front,
  /// control/front_obstacle.hpp); +inf: clear
  double obstacle_distance = std::numeric_limits<double>::infinity();
  /// the map stage's validated place (Emmi 2021 Table 1); nullopt: the stage is off
  std::optional<map::Place> place;
};

/// The navigator's answer.
struct NavOutput {
  core::Twist2 cmd;  ///< the command, unless `control` is set
  /// In a row: what the path controller is to follow; the caller sets ControlInput::dt and
  /// obstacle_distance and replaces `cmd` by the controller's answer.
  std::optional<control::ControlInput> control;
  bool reset_tracking = false;    ///< a turn started: reset the tracker and the controller
  bool reset_end_of_row = false;  ///< a new corridor: reset the end-of-row detector
  NavState state = NavState::in_row;
  StopReason stop_reason = StopReason::none;
  std::vector<NavEvent> events;  ///< what happened this step
  int corridor = -1;             ///< corridor of the plan being served / entered
  int served = 0;                ///< corridors driven end to end
  /// In a turn or the headland: this frame's row-end points, one per cluster by the row_ends
  /// policy (odom frame; 003 sec. II-C, what its Table II scores against the poles)
  std::vector<Eigen::Vector2d> row_end_points;
};

/// What a state is planned to take, from its geometry when it starts (exiting: the distance
/// left to the exit point; a turn: its planned paths and rotations; entering: the maximum
/// entry depth). The watchdog's budgets are multiples of it.
struct StateEffort {
  double distance = 0.0;  ///< [m]
  double time = 0.0;      ///< [s] at the state's speeds
};

/// The mission state machine. step() / hold() never throw.
class Navigator {
 public:
  /// `order`: resolved corridor order (resolve_order); the robot starts in order.front().
  /// `end_of_row`: the end-of-row detector's geometry: its box's near edge is the row end's
  /// distance when the detector gives none, its extent_distance the end_withdraw_reach left 0.
  Navigator(const NavigatorConfig& config, std::vector<int> order, TurnSide first_turn,
            const EndOfRowConfig& end_of_row = {});

  /// One LiDAR frame.
  NavOutput step(const NavInput& in);
  /// Between frames (physics rate): refreshes odometry-closed parts (rotations, line following)
  /// with the latest pose; elsewhere (in a row) repeats `last_cmd`, the command last sent. Cheap.
  NavOutput hold(double stamp, const core::Pose2& T_odom_base, const core::Twist2& last_cmd);

  NavState state() const { return state_; }
  /// Planned effort of the current state (nullopt in a row and in terminal states).
  std::optional<StateEffort> effort() const;
  /// Safe stop from outside (NavStack's watchdog): state safe_stop with `reason`, an event.
  NavOutput abort(StopReason reason, double stamp, const std::string& why);
  StopReason stop_reason() const { return reason_; }
  /// Row-end points estimated so far (odom frame): the ends of every corridor left.
  const std::vector<Eigen::Vector2d>& row_ends_odom() const { return row_ends_; }
  /// Turns completed.
  int turns() const { return turns_; }
  const std::vector<int>& order() const { return order_; }
  /// The manoeuvre in progress (null outside the headland).
  const HeadlandManoeuvre* manoeuvre() const { return manoeuvre_.get(); }

 private:
  void in_row(const NavInput& in, NavOutput& out);
  /// in_row -> exiting at the row end (`why` starts the row_end event's message).
  void start_exit(const NavInput& in, NavOutput& out, const std::string& why);
  void exiting(const core::Pose2& T, NavOutput& out, double stamp);
  /// exiting -> in_row when the followed rows go on beyond the declared end (withdraw_end).
  bool withdraw_end(const NavInput& in, NavOutput& out);
  /// Exiting, each frame: whether a followed row's returns run on past the declared end
  /// (exit_rows_run_on_); until they do, the exit ends at most end_withdraw_reach past it.
  void bound_exit(const NavInput& in);
  /// This frame's returns along a followed row fill row_end_estimate.settle_distance of it past
  /// the declared end (withdraw_end, bound_exit).
  bool rows_run_on_past_end(const NavInput& in) const;
  void turning(const NavInput* in, const core::Pose2& T, NavOutput& out, double stamp);
  void entering(const NavInput* in, const core::Pose2& T, NavOutput& out, double stamp);
  static std::string fmt(double v);
  void start_turn(const core::Pose2& T, NavOutput& out, double stamp);
  void stop(StopReason reason, NavOutput& out, double stamp, const std::string& why);
  /// stop(obstacle) outside a row: `where` (the check's message) and the state it came in.
  void stop_for_obstacle(NavOutput& out, double stamp, const std::string& where);
  /// The stop's message when >= obstacle_min_points points lie in the stop box, else nullopt.
  std::optional<std::string> obstacle_ahead(const NavInput& in) const;
  /// The stop's message when >= obstacle_min_points points lie within the circle the footprint
  /// sweeps rotating in place about base_link (plus rotation_clearance), else nullopt.
  std::optional<std::string> obstacle_in_swing(const NavInput& in) const;
  /// The stop's message once a front obstacle has held the robot for blocked_timeout.
  std::optional<std::string> held_by_obstacle(const NavInput& in);
  /// [m] how far past the row end the exit drives (exit_distance, or the canopy's reach).
  double exit_distance(const NavInput& in) const;
  core::Twist2 follow_line(const core::Line2& line, const core::Pose2& T, double v) const;
  NavOutput finish(NavOutput out);

  NavigatorConfig config_;
  std::vector<int> order_;
  std::vector<CorridorChange> changes_;
  double end_box_near_ = 0.0;
  double exit_distance_ = 0.0;  // [m] this row's exit: exit_distance or the canopy's reach
  Eigen::Vector2d declared_end_ = Eigen::Vector2d::Zero();  // [m] odom: start_exit's row end
  bool exit_rows_run_on_ = false;  // this exit saw the rows run on past declared_end_ (bound_exit)
  NavState state_ = NavState::in_row;
  StopReason reason_ = StopReason::none;
  bool at_rows_ = false;      // the end of row is armed (the robot has reached the rows)
  int narrow_count_ = 0;      // this corridor's frames with a lane narrower than the robot
  int lane_frames_ = 0;       // this corridor's frames with both rows followed
  bool narrow_said_ = false;  // narrow_corridor reported for this corridor
  void check_lane(const NavInput& in, NavOutput& out);
  std::size_t leg_ = 0;  // index in order_ of the corridor being served
  int served_ = 0, turns_ = 0;
  double last_seen_ = -1.0, last_stamp_ = 0.0;
  std::optional<double> blocked_since_;  // [s] in_row: held by a front obstacle since
  double spacing_ = 0.0;  // [m] spacing of the turn in progress (entry gate, row ends)
  RowEndEstimator ends_;  // the corridor being left
  std::unique_ptr<HeadlandManoeuvre> manoeuvre_;
  RobotLimits robot_;
  std::vector<Eigen::Vector2d> row_ends_;
  std::optional<core::Line2> entry_seen_;   // target corridor centre seen while entering (odom)
  std::optional<StateEffort> exit_effort_;  // set when the exit starts
  std::optional<map::Place> place_;         // the map's place at the last frame (place_gate)
};

}  // namespace rownav::navigate

template <>
struct rownav::core::EnumNames<rownav::navigate::NavState> {
  using E = rownav::navigate::NavState;
  static constexpr std::array<std::pair<E, std::string_view>, 7> values{
      {{E::in_row, "in_row"},
       {E::exiting, "exiting"},
       {E::turning, "turning"},
       {E::headland, "headland"},
       {E::entering, "entering"},
       {E::done, "done"},
       {E::safe_stop, "safe_stop"}}};
};

template <>
struct rownav::core::EnumNames<rownav::navigate::StopReason> {
  using E = rownav::navigate::StopReason;
  static constexpr std::array<std::pair<E, std::string_view>, 9> values{
      {{E::none, "none"},
       {E::done, "done"},
       {E::perception_lost, "perception_lost"},
       {E::obstacle, "obstacle"},
       {E::place_contradicts_plan, "place_contradicts_plan"},
       {E::timeout, "timeout"},
       {E::budget_exceeded, "budget_exceeded"},
       {E::odometry_implausible, "odometry_implausible"},
       {E::moved_while_held, "moved_while_held"}}};
};

template <>
struct rownav::core::EnumNames<rownav::navigate::NavEventKind> {
  using E = rownav::navigate::NavEventKind;
  static constexpr std::array<std::pair<E, std::string_view>, 14> values{
      {{E::row_end, "row_end"},
       {E::exit_done, "exit_done"},
       {E::turn_started, "turn_started"},
       {E::row_passed, "row_passed"},
       {E::reanchored, "reanchored"},
       {E::turn_finished, "turn_finished"},
       {E::entered_corridor, "entered_corridor"},
       {E::safe_stop, "safe_stop"},
       {E::mission_done, "mission_done"},
       {E::input_stale, "input_stale"},
       {E::input_resumed, "input_resumed"},
       {E::narrow_corridor, "narrow_corridor"},
       {E::row_end_withdrawn, "row_end_withdrawn"},
       {E::moved_while_held, "moved_while_held"}}};
};
