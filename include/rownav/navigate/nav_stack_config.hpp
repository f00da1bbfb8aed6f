#pragma once
/// @file nav_stack_config.hpp The settings of navigate::NavStack: the navigator (mission state
/// machine, headland turns), the end-of-row detector, the stack's own input handling and the
/// map stage, in one YAML file (config/navigate/<crop>.yaml: `navigator:`, `end_of_row:`,
/// `stack:` and `place:` sections).
/// The robot's geometry, limits and odometry model come from the robot file (not from YAML
/// here): the adapters fill `robot`, `limits` and `localizer`.
///
/// The end-of-row height band and look-ahead box depend on the canopy (Lan 2021,
/// 001_b5f4b55a1b95775a.txt eq. 24 gives 0.5-1.3 m, 3-5 m for vines); `rownav run` picks the
/// crop's file like the detection config (config/detect/<crop>.yaml).
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>

#include "rownav/control/front_obstacle.hpp"
#include "rownav/control/velocity_limits.hpp"
#include "rownav/core/config_fields.hpp"
#include "rownav/localize/localizer.hpp"
#include "rownav/localize/odometry_scale_estimator.hpp"
#include "rownav/navigate/end_of_row.hpp"
#include "rownav/navigate/navigator.hpp"
#include "rownav/navigate/obstacle_points.hpp"
#include "rownav/navigate/place_input.hpp"

namespace rownav::navigate {

/// Where NavStack's T_odom_base comes from.
enum class OdometryInput : std::uint8_t {
  wheels_imu,  ///< its own localize::Localizer fed with encoders, IMU (and GNSS)
  external     ///< poses given with on_odometry (a robot's own odometry, e.g. nav_msgs/Odometry)
};

/// How far NavStack runs the chain.
enum class StackMode : std::uint8_t {
  navigate,  ///< detect -> track -> end of row -> navigator -> controller -> limits
  track,     ///< detect -> track (open-loop analysis: `rownav track`)
  detect     ///< detect only (`rownav detect`): no odometry needed
};

/// NavStack's watchdog (issue 13, "driving blind"): no motion from stale inputs, and a budget
/// for every state whose end is decided by odometry alone.
struct WatchdogConfig {
  /// [s] no new LiDAR frame for this long past its sweep period: zero command until one comes
  /// (the navigator's perception_timeout in a row; here in every state)
  double lidar_timeout = 0.5;
  double odometry_timeout = 0.2;  ///< [s] no odometry sample for this long: zero command
  /// [-] exiting, a turn or an entry may take this many times its planned distance and time
  /// (Navigator::effort) before a safe stop `budget_exceeded`
  double budget_factor = 2.0;
  double budget_time_margin = 3.0;      ///< [s] added to the time budget
  double budget_distance_margin = 2.0;  ///< [m] added to the distance budget
  /// Odometry against the commands: over the last `plausibility_window` seconds the robot was
  /// commanded at least `plausibility_distance` metres forward or back but the odometry moved
  /// less than `plausibility_ratio` of that -> safe stop `odometry_implausible` (a frozen or
  /// broken encoder, or stalled wheels: driving on would be blind)
  double plausibility_window = 2.0;    ///< [s]
  double plausibility_distance = 1.0;  ///< [m]
  double plausibility_ratio = 0.25;    ///< [-]
  /// While held (NavStack::set_held: paused, or not started), the tracked offset from the corridor
  /// centre moved this far from where it was when the hold began: event moved_while_held (the
  /// robot was pushed or carried; a resume steers to the centre of whatever corridor is tracked
  /// then, issue 15). Three times the offset's wander for a standing robot (3.3 cm in 10 s on a
  /// 2D scan with 2 cm range noise, tests/navigate/nav_stack_hold_test.cpp), and under a third
  /// of a 0.75 m row crop's half corridor, so a push into the next corridor is reported before
  /// the tracker takes that corridor for its own
  double held_move_lateral = 0.1;       ///< [m]
  double held_move_heading_deg = 10.0;  ///< [deg] the same for the heading to the corridor
  /// A hold that began in a row after the mission had driven also decides whether the robot may
  /// resume (NavStack::resume_blocker): when the tracked offset from the corridor centre moves
  /// by more than this fraction of the tracked row spacing since the hold began (the robot
  /// stands on or beyond a followed row), or from one tracked frame to the next (the tracker
  /// took another corridor: neighbouring corridor centres lie one spacing apart, and a push
  /// moves the robot a few centimetres between two frames), the resume is a safe stop
  /// `moved_while_held` instead (issue 15). Half a spacing: a row's centre line
  double held_corridor_fraction = 0.5;  ///< [-] of the row spacing

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("lidar_timeout", s.lidar_timeout);
    v("odometry_timeout", s.odometry_timeout);
    v("budget_factor", s.budget_factor);
    v("budget_time_margin", s.budget_time_margin);
    v("budget_distance_margin", s.budget_distance_margin);
    v("plausibility_window", s.plausibility_window);
    v("plausibility_distance", s.plausibility_distance);
    v("plausibility_ratio", s.plausibility_ratio);
    v("held_move_lateral", s.held_move_lateral);
    v("held_move_heading_deg", s.held_move_heading_deg);
    v("held_corridor_fraction", s.held_corridor_fraction);
  }
  void validate() const {
    core::check_positive(lidar_timeout, "lidar_timeout");
    core::check_positive(odometry_timeout, "odometry_timeout");
    core::check(budget_factor >= 1.0, "budget_factor", "must be >= 1");
    core::check_non_negative(budget_time_margin, "budget_time_margin");
    core::check_non_negative(budget_distance_margin, "budget_distance_margin");
    core::check_positive(plausibility_window, "plausibility_window");
    core::check_positive(plausibility_distance, "plausibility_distance");
    core::check_range(plausibility_ratio, 0.0, 1.0, "plausibility_ratio");
    core::check_positive(held_move_lateral, "held_move_lateral");
    core::check_range(held_move_heading_deg, 0.1, 180.0, "held_move_heading_deg");
    core::check_range(held_corridor_fraction, 0.05, 1.0, "held_corridor_fraction");
  }
};

/// NavStack's own settings (input handling between the sensors and the chain).
struct StackConfig {
  StackMode mode = StackMode::navigate;                ///< how far the chain runs
  OdometryInput odometry = OdometryInput::wheels_imu;  ///< pose source
  /// Level each 3D sweep by the gravity the IMU measured during it (a rolling base shifts a row
  /// seen at height h by h sin(roll); rownav, BENCHMARK.md issue 4)
  bool level_by_gravity = true;
  /// [deg] a gravity "up" tilted further than this from the base's z is not trusted and the
  /// sweep is not levelled: no field robot drives a 58 % slope, so such a reading is the
  /// accelerometer dominated by shocks or a mis-set IMU mount (rownav)
  double max_level_tilt_deg = 30.0;
  /// [s] sweep duration for levelling when two successive sweep stamps do not give it
  /// (10 Hz: OS1, VLP-16 as in Nehme 2021 sec. 5)
  double sweep_period = 0.1;
  double imu_history = 1.0;  ///< [s] IMU samples kept for levelling
  /// external odometry: the yaw rate from the gyro when a sample is fresher than gyro_max_age
  bool gyro_yaw_rate = true;
  double gyro_max_age = 0.5;       ///< [s]
  double odometry_history = 2.0;   ///< [s] external poses kept
  double max_extrapolation = 0.2;  ///< [s] external pose extrapolated past the newest one
  double command_period = 0.01;    ///< [s] acceleration-limit step of the first command (100 Hz)
  double max_frame_dt = 1.0;       ///< [s] controller dt is clamped to this (a gap in frames)
  /// Obstacle rectangle of the controllers' slow-down (Bertoglio 2023 sec. II-B); its width and
  /// front x are the robot's (no margin: the corridor's canopy faces are within 0.1 m of a
  /// robot in a narrow row), an obstacle is >= 3 points after preprocessing (a lone shoot or
  /// weed blade stalled the demo at zero speed with 1 point and a 0.1 m margin).
  control::FrontRectConfig front = {.margin = 0.0, .min_points = 3};
  WatchdogConfig watchdog;       ///< stale inputs and state budgets
  ObstacleBandConfig obstacles;  ///< which 3D points are obstacles (stop, slow-down)
  /// A planar scan's points in front of the robot are obstacles (stop, slow-down). false: the
  /// robot drives over what its scanner sees between the rows: a weeding robot whose scanner is
  /// low enough to cut vegetables cuts the weeds it is there to remove, and a plane gives no
  /// height to tell them from a post (Malavazi 2018's Oz navigation has no obstacle stop; use a
  /// 3D sensor, whose obstacles go by height, where people or posts can be in the corridor)
  bool planar_obstacles = true;
  /// The wheel odometry's alpha measured online from the LiDAR frames of straight stretches
  /// (Bertoglio 2023 eq. (2); issue 11). Only with odometry = wheels_imu and without GNSS.
  localize::OdometryScaleConfig odometry_scale;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("mode", s.mode);
    v("odometry", s.odometry);
    v("level_by_gravity", s.level_by_gravity);
    v("max_level_tilt_deg", s.max_level_tilt_deg);
    v("sweep_period", s.sweep_period);
    v("imu_history", s.imu_history);
    v("gyro_yaw_rate", s.gyro_yaw_rate);
    v("gyro_max_age", s.gyro_max_age);
    v("odometry_history", s.odometry_history);
    v("max_extrapolation", s.max_extrapolation);
    v("command_period", s.command_period);
    v("max_frame_dt", s.max_frame_dt);
    v("front", s.front);
    v("watchdog", s.watchdog);
    v("obstacles", s.obstacles);
    v("planar_obstacles", s.planar_obstacles);
    v("odometry_scale", s.odometry_scale);
  }
  void validate() const {
    core::check_range(max_level_tilt_deg, 0.0, 90.0, "max_level_tilt_deg");
    core::check_positive(sweep_period, "sweep_period");
    core::check_positive(imu_history, "imu_history");
    core::check_positive(gyro_max_age, "gyro_max_age");
    core::check_positive(odometry_history, "odometry_history");
    core::check_non_negative(max_extrapolation, "max_extrapolation");
    core::check_positive(command_period, "command_period");
    core::check_positive(max_frame_dt, "max_frame_dt");
    core::validate_nested(front, "front");
    core::validate_nested(watchdog, "watchdog");
    core::validate_nested(obstacles, "obstacles");
    core::validate_nested(odometry_scale, "odometry_scale");
  }
};

/// Everything NavStack is built from. Every default is the member's own.
struct NavStackConfig {
  NavigatorConfig navigator;  ///< mission state machine and headland turns
  EndOfRowConfig end_of_row;  ///< when the rows end ahead
  StackConfig stack;          ///< input handling
  PlaceConfig place;          ///< the map stage: place, key locations (Emmi 2021; off by default)
  // From the robot file (io::nav_stack_robot), not from this YAML file:
  RobotLimits robot;                    ///< footprint and turn ability
  control::VelocityLimits limits;       ///< applied to every command, as a base controller would
  localize::LocalizerConfig localizer;  ///< wheel odometry model and EKF noise

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("navigator", s.navigator);
    v("end_of_row", s.end_of_row);
    v("stack", s.stack);
    v("place", s.place);
  }
  void validate() const {
    core::validate_nested(navigator, "navigator");
    core::validate_nested(end_of_row, "end_of_row");
    core::validate_nested(stack, "stack");
    core::validate_nested(place, "place");
    core::validate_nested(limits, "limits");
  }
};

}  // namespace rownav::navigate

template <>
struct rownav::core::EnumNames<rownav::navigate::OdometryInput> {
  using E = rownav::navigate::OdometryInput;
  static constexpr std::array<std::pair<E, std::string_view>, 2> values{
      {{E::wheels_imu, "wheels_imu"}, {E::external, "external"}}};
};

template <>
struct rownav::core::EnumNames<rownav::navigate::StackMode> {
  using E = rownav::navigate::StackMode;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::navigate, "navigate"}, {E::track, "track"}, {E::detect, "detect"}}};
};
