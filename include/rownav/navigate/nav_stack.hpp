#pragma once
/// @file nav_stack.hpp The one per-frame entry point of rownav: raw stamped sensor samples in,
/// the command to send, the mission state, the deviations and the events out.
///
/// NavStack owns the chain sensor samples -> localize (wheel odometry + IMU EKF, or an external
/// odometry) -> gravity levelling -> detection pipeline -> tracker -> end of row -> navigator ->
/// controller (dt, obstacle distance) -> velocity limits, and beside the chain, when
/// PlaceConfig::enabled, the map stage (Emmi 2021: place, key locations, topological map). The
/// simulator runner, the ROS node, `rownav track`, `rownav detect` and the test harnesses only
/// convert their input and call it, the way kiss-icp's ROS wrapper only calls its pipeline class.
///
/// Samples may come in any order: one older than the newest of its stream, a duplicate or a
/// non-finite stamp is dropped and counted (stats()), never a throw.
#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rownav/control/controller.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/core/scan2d.hpp"
#include "rownav/core/sensor_samples.hpp"
#include "rownav/detect/pipeline.hpp"
#include "rownav/localize/localizer.hpp"
#include "rownav/localize/pose_history.hpp"
#include "rownav/map/place_estimator.hpp"
#include "rownav/navigate/canopy_reach.hpp"
#include "rownav/navigate/ground_cover.hpp"
#include "rownav/navigate/nav_stack_config.hpp"
#include "rownav/navigate/navigator.hpp"
#include "rownav/navigate/place_input.hpp"
#include "rownav/track/row_tracker.hpp"

namespace rownav::navigate {

/// The replaceable algorithms, built by name by the adapters (io registries).
struct NavStackParts {
  std::unique_ptr<detect::DetectionPipeline> pipeline;
  std::unique_ptr<track::RowTracker> tracker;           ///< null in StackMode::detect
  std::unique_ptr<control::PathController> controller;  ///< null unless StackMode::navigate
};

/// What one LiDAR frame gave.
struct FrameReport {
  double stamp = 0.0;                ///< [s] frame (sweep start) stamp
  core::RowObservation observation;  ///< detector output (base frame)
  /// nullopt: no odometry at the frame, or detect mode
  std::optional<track::RowTracking> tracking;
  EndOfRowResult end_of_row;
  /// the map stage's estimate of this frame (nullopt: disabled, detect mode or no odometry)
  std::optional<map::PlaceEstimate> place;
  bool levelled = false;  ///< the sweep was levelled by the IMU's gravity
  double latency = 0.0;   ///< [s] wall time of the frame through the chain
};

/// Whether the inputs are fresh enough to move (NavStack's watchdog).
enum class InputHealth : std::uint8_t { ok, lidar_stale, odometry_stale };

/// The answer of command().
struct NavCommand {
  double stamp = 0.0;
  core::Twist2 cmd;  ///< to send (limited; zero in done / safe_stop or without odometry)
  NavState state = NavState::in_row;
  StopReason stop_reason = StopReason::none;
  int corridor = -1;  ///< corridor of the plan being served / entered
  int served = 0;
  std::vector<NavEvent> events;      ///< what happened in this call
  std::optional<FrameReport> frame;  ///< the LiDAR frame processed in this call, if any
  /// a turn's frame: its row-end points (odom frame, NavOutput::row_end_points)
  std::vector<Eigen::Vector2d> row_end_points;
  /// the map stage's validated place (Emmi 2021 Table 1; unknown when disabled)
  map::Place place = map::Place::unknown;
  std::vector<PlaceKey> key_locations;   ///< key locations validated in this call (odom frame)
  InputHealth health = InputHealth::ok;  ///< not ok: the command is zero until inputs are fresh
  double lidar_age = 0.0;     ///< [s] since the newest LiDAR frame was complete (inf: none yet)
  double odometry_age = 0.0;  ///< [s] since the newest odometry sample (inf: none yet)
};

/// Inputs dropped (late, duplicate, non-finite) and frames not processed, per stream.
struct NavStackStats {
  std::uint64_t encoders = 0, imu = 0, gnss = 0, odometry = 0, frames = 0;  ///< accepted
  std::uint64_t dropped_encoders = 0, dropped_imu = 0, dropped_gnss = 0, dropped_odometry = 0;
  std::uint64_t dropped_frames = 0;   ///< older than (or as old as) the last frame
  std::uint64_t replaced_frames = 0;  ///< a newer frame came before command() processed it
  std::uint64_t late_commands = 0;    ///< command() with a stamp older than the previous one
};

/// The watchdog's budget of a state: factor x its planned time / distance + the margins.
/// Returns a reason ("took 31.2 s / 4.0 m, budget 13.6 s / 10.4 m") when exceeded.
std::optional<std::string> budget_exceeded(const StateEffort& planned, double elapsed,
                                           double distance, const WatchdogConfig& config);

/// The navigation stack. Not thread-safe (feed it from one thread); never throws after
/// construction.
class NavStack {
 public:
  /// Validates `config` and the parts (std::invalid_argument naming the field); `order` is the
  /// resolved corridor order (resolve_order), the robot starting in order.front().
  NavStack(const NavStackConfig& config, NavStackParts parts, std::vector<int> order = {0},
           TurnSide first_turn = TurnSide::left);
  ~NavStack();
  NavStack(const NavStack&) = delete;
  NavStack& operator=(const NavStack&) = delete;

  /// Wheel counts; false when dropped (stamp not newer than the newest one, or not finite).
  bool on_encoders(const core::WheelEncoderSample& s);
  void on_imu(const core::ImuSample& s);
  void on_gnss(const core::GnssFix& s);
  /// A pose of an external odometry (StackConfig::odometry = external); false when it was
  /// dropped (not newer than the newest, or not finite).
  bool on_odometry(const localize::StampedPose& s);
  /// A 3D sweep in the LiDAR frame (per-point times); processed by the next command().
  /// `labels`: optional semantic labels for the map stage, one per point in the cloud's order
  /// (a camera detector, the simulator's truth); empty: the geometric default (place_input.hpp).
  void on_cloud(core::PointCloud cloud, std::vector<map::PointLabel> labels = {});
  /// A 2D scan in the LiDAR frame; processed by the next command().
  void on_scan(core::Scan2D scan);
  /// The command at `stamp`: processes the pending frame if there is one, else refreshes the
  /// odometry-closed manoeuvres between frames.
  NavCommand command(double stamp);
  /// Begins a new mission from where the robot stands (an operator's start after a stop, or
  /// after done / safe_stop): the navigator with the constructor's corridor order, the
  /// tracker, controller, end-of-row detector, map stage, obstacle cover and the watchdog's
  /// state budgets start afresh; the localisation, the sample streams and the sweep period
  /// are kept, so the odom frame stays continuous (REP 105). The robot is to stand in the
  /// plan's first corridor, as at construction. A frame not yet processed is kept.
  void restart_mission();
  /// restart_mission() with another plan: `order` (resolve_order's corridors, not empty) and the
  /// side of its first turn, for an operator who has put the robot at the entrance of that
  /// plan's first corridor (issue 15: resume a field from its third corridor after a battery
  /// change). Later restarts keep this plan. Throws std::invalid_argument on an empty order.
  void restart_mission(std::vector<int> order, TurnSide first_turn);
  /// Holds the mission (an operator's pause, or a mission not started yet) or lets it go on.
  /// While held, frames still run perception (levelling, detection, tracking, end of row, map
  /// stage), so the row models are as current as the last frame when the mission resumes; the
  /// navigator only holds its state (as between frames), the controller is not run, and the
  /// command is zero (zero, not ramped down). The watchdog keeps watching: stale inputs are
  /// reported, and the time of a hold in an odometry-closed manoeuvre counts into its budget.
  /// A hold also watches the rows: when they say the robot moved (StackConfig::watchdog
  /// held_move_lateral / held_move_heading_deg) or are lost, the event moved_while_held is sent
  /// once per hold. A hold that began in a row after the mission had driven (an operator's
  /// pause, not the wait before a start, when the operator places the robot) also guards the
  /// resume: if the rows were lost during it, or the robot left the corridor
  /// (held_corridor_fraction), releasing it ends the mission in a safe stop `moved_while_held`
  /// instead of steering into whatever corridor is tracked then; restart_mission() begins again
  /// from where it stands.
  void set_held(bool held);
  bool held() const { return held_; }
  /// While held: why releasing the hold would end in a safe stop (the robot was carried out of
  /// the rows or into another corridor), or nullopt when it may resume.
  std::optional<std::string> resume_blocker() const;

  /// T_odom_base at `stamp` from the configured source (nullopt before any odometry).
  std::optional<core::Pose2> T_odom_base(double stamp) const;
  /// Body velocity estimate (zero before any odometry).
  core::Twist2 twist() const;

  const Navigator& navigator() const { return *navigator_; }
  const detect::DetectionPipeline& pipeline() const { return *parts_.pipeline; }
  const localize::Localizer& localizer() const { return localizer_; }
  /// The online estimate of the odometry's alpha (StackConfig::odometry_scale).
  const localize::OdometryScaleEstimator& odometry_scale() const { return scale_; }
  const NavStackStats& stats() const { return stats_; }
  const NavStackConfig& config() const { return config_; }
  /// The map stage (null when PlaceConfig::enabled is false).
  const map::PlaceEstimator* place_estimator() const { return place_.get(); }

 private:
  struct Pending;
  void begin_mission();  // navigator and map stage for order_ / first_turn_
  FrameReport process_frame(Pending& frame, const std::optional<core::Pose2>& T);
  core::RowObservation detect_frame(Pending& frame, bool& levelled);
  void estimate_place(const Pending& frame, FrameReport& report, const core::Pose2& T);
  NavOutput navigate_frame(double stamp, const core::Pose2& T, FrameReport& report);
  ObstacleBandConfig obstacle_band(const core::PointCloud& cloud_base);  // this frame's band
  double robot_top() const;  // [m] base z above which points pass over the robot
  void drop_row_canopy(const core::PointCloud& cloud_base, const ObstacleBandConfig& band,
                       const track::RowTracking& tracking, std::vector<Eigen::Vector2f>& points);
  void measure_period(double frame_stamp);
  bool accept_frame(double frame_stamp);  // false: dropped (late, duplicate, not finite)
  void apply(const NavOutput& out);
  core::Twist2 limit(const core::Twist2& cmd, double stamp);
  void watch_inputs(NavCommand& c, NavOutput& out, double stamp);
  void watch_budget(NavOutput& out, double stamp, const std::optional<core::Pose2>& T);
  void watch_odometry(NavOutput& out, double stamp, const std::optional<core::Pose2>& T);
  void watch_hold(const FrameReport& report, NavOutput& out, double stamp);
  void safe_stop(NavOutput& out, StopReason reason, double stamp, const std::string& why);

  NavStackConfig config_;
  NavStackParts parts_;
  std::vector<int> order_;  // the constructor's plan, for restart_mission()
  TurnSide first_turn_;
  std::unique_ptr<EndOfRowDetector> end_of_row_;
  std::unique_ptr<Navigator> navigator_;
  std::unique_ptr<map::PlaceEstimator> place_;  // null: map stage disabled
  localize::Localizer localizer_;
  localize::OdometryScaleEstimator scale_;
  localize::PoseHistory external_;
  PlaceInput place_input_;       // after the members built before validation (config_.validate())
  GroundCoverEstimator cover_;   // validated config
  CanopyReachEstimator canopy_;  // validated config
  std::deque<core::ImuSample> imu_;
  std::vector<core::ImuSample> imu_buf_;  // imu_ made contiguous for levelling, reused per frame
  std::unique_ptr<Pending> pending_;
  std::optional<double> last_frame_stamp_, last_command_stamp_,
      last_cloud_stamp_;  // last_cloud_stamp_: any frame
  double sweep_period_ = 0.0;
  double last_encoder_ = -1e300, last_gnss_ = -1e300;
  core::Twist2 nav_cmd_, sent_cmd_;  // navigator's last command, the last limited command
  bool held_ = false;                // set_held(): perception only, command zero
  NavStackStats stats_;
  // Watchdog: input health, and the current state's start, distance driven and budget.
  InputHealth health_ = InputHealth::ok;
  bool inputs_seen_ = false;
  int phase_ = -1;
  double phase_start_ = 0.0, phase_distance_ = 0.0;
  std::optional<core::Pose2> phase_last_T_;
  std::optional<StateEffort> phase_effort_;
  struct Motion {
    double stamp, commanded, measured;  // [s], [m] since the previous command
  };
  std::deque<Motion> motion_;
  double commanded_sum_ = 0.0, measured_sum_ = 0.0;
  std::optional<core::Pose2> motion_last_T_;
  // Hold: the tracked offset and heading to the corridor of the last tracked frame, as they were
  // when the hold began, and whether the move was reported.
  std::optional<Eigen::Vector2d> last_tracked_, hold_reference_;
  bool hold_reported_ = false;
  // Resume guard: whether the mission has commanded since it began, whether the current hold
  // guards its resume, why it may not resume, and a refused resume still to be applied.
  bool driven_ = false, hold_guards_resume_ = false;
  std::optional<std::string> hold_blocker_, resume_refused_;
};

}  // namespace rownav::navigate
