#pragma once
/// @file closed_loop_runner.hpp A whole mission in the simulator with navigate::NavStack closed
/// on the simulated sensors: the runner only hands NavStack the simulator's samples and the
/// simulator NavStack's command, and records what a report needs; deterministic per seed.
#include <Eigen/Core>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rownav/control/controller.hpp"
#include "rownav/navigate/end_of_row.hpp"
#include "rownav/navigate/mission_plan.hpp"
#include "rownav/navigate/nav_stack.hpp"
#include "rownav/navigate/navigator.hpp"
#include "rownav/sim/field.hpp"
#include "rownav/sim/pinhole_camera.hpp"
#include "rownav/sim/robot.hpp"
#include "rownav/sim/simulator.hpp"
#include "rownav/sim/truth_labeller.hpp"
#include "rownav/track/row_tracker.hpp"

namespace rownav::io {

using TrackerFactory = std::function<std::unique_ptr<track::RowTracker>()>;
using ControllerFactory = std::function<std::unique_ptr<control::PathController>()>;

/// Everything a closed-loop run needs (files already loaded).
struct ClosedLoopSetup {
  const sim::Field* field = nullptr;  ///< must outlive the run
  sim::RobotConfig robot;
  sim::SimConfig sensors;
  navigate::MissionPlan mission;
  /// navigator, end of row and stack settings; robot, limits and localizer are filled from
  /// `robot` and `sensors` by the runner (nav_stack_robot)
  navigate::NavStackConfig nav;
  std::string detector = "hough_skew";
  std::filesystem::path detect_config;  ///< empty: detector defaults
  TrackerFactory make_tracker;
  ControllerFactory make_controller;
  double time_limit = 1200.0;  ///< [s] simulated; the run stops with reason `timeout`
  /// When set, every input handed to NavStack is also written, in order, to this new recording
  /// directory (samples + inputs.csv with each command the stack answered): its replay through
  /// io::replay_input_log must give the same commands.
  std::filesystem::path record_inputs;
  /// [s] simulated on with a zero command after a safe stop, so that the robot comes to rest
  /// and the samples show where (the fault runs of issue 13: the clearance to a person)
  double settle = 0.0;
  double lead_in = 1.5;  ///< [m] start this far before the first corridor's entrance
  /// [m] start this far left (+) or right (-) of the first corridor's centre line (brief: the
  /// robot off-centre; an operator rarely puts it on the centre line)
  double start_offset = 0.0;
  double start_yaw = 0.0;  ///< [rad] start heading from the corridor direction (left +): yawed
  /// The map stage's labels (nav.place.enabled): every sweep's points labelled from the
  /// simulator's truth by sim::TruthLabeller with `labeller`'s false-positive / negative rates
  /// (a stand-in for Emmi 2021's camera detector, Fig. 2b); false: NavStack's geometric default
  bool truth_labels = true;
  sim::TruthLabellerConfig labeller;
  /// Camera labels instead (`rownav run --labels camera`, issue 12): a simulated camera
  /// (`camera`, sim::PinholeCamera) rendered at every `camera_every`-th sweep, its
  /// vision::ExcessGreenDetector boxes, every sweep labelled by vision::CameraLabeller from the
  /// last image (Emmi 2021 Fig. 2b: several laser frames from one image). Overrides truth_labels.
  bool camera_labels = false;
  sim::PinholeCameraConfig camera;
  int camera_every = 5;  ///< [-] sweeps per image (10 Hz LiDAR: a 2 Hz camera) (rownav)
  std::function<void(double sim_time, double fraction)> progress;  ///< optional
};

/// One ground-truth sample of the run (20 Hz).
struct RunSample {
  double stamp = 0.0;
  core::Pose2 T_world_base;  ///< truth
  core::Pose2 T_odom_base;   ///< what the stack believed
  sim::Place place = sim::Place::outside;
  int corridor = -1;          ///< true corridor (lane) or -1
  int planned_corridor = -1;  ///< navigator's corridor
  navigate::NavState state = navigate::NavState::in_row;
  double lateral_error = 0.0;  ///< [m] true, from the corridor centre
  double heading_error = 0.0;  ///< [rad] true
  core::Twist2 twist, cmd;
  int plants_crushed = 0;
  bool collision = false;  ///< footprint over a post (or touching a person) this sample
  /// [m] footprint to the walking person of the simulator's faults (inf: none)
  double obstacle_clearance = std::numeric_limits<double>::infinity();
};

/// Per LiDAR frame, in a row: the tracker against the truth.
struct FrameSample {
  double stamp = 0.0;
  double latency = 0.0;  ///< [s] detection + tracking + end of row + navigator
  bool in_row = false;   ///< navigator in_row and truth in a lane
  track::TrackStatus status = track::TrackStatus::lost;
  double lateral_error = 0.0, true_lateral_error = 0.0;  ///< [m]
  double heading_error = 0.0, true_heading_error = 0.0;  ///< [rad]
  double row_spacing = 0.0;                              ///< [m] tracker's
  std::vector<double> slope_errors, intercept_errors;    ///< followed rows vs truth
};

/// A plant the footprint ran over: where, when and in which navigator state (issue 11: "find
/// where the plants are crushed").
struct CrushRecord {
  double stamp = 0.0;        ///< [s] ground-truth sample that first saw it crushed
  Eigen::Vector2d position;  ///< [m] plant centre, world frame
  double radius = 0.0;       ///< [m] its crushable radius (stem, head)
  navigate::NavState state = navigate::NavState::in_row;
  Eigen::Vector2d robot_xy;  ///< [m] true base position then
};

/// Per LiDAR frame with the map stage on: its validated place against the truth.
struct PlaceSample {
  double stamp = 0.0;
  map::Place estimated = map::Place::unknown;  ///< NavCommand::place
  sim::Place truth = sim::Place::outside;
};

/// A key location the map stage validated, mapped into the world by the robot's true pose at
/// validation (as the row ends: the error is that of the estimate relative to the robot).
struct KeyLocationSample {
  navigate::PlaceKey key;                           ///< odom frame
  Eigen::Vector2d world = Eigen::Vector2d::Zero();  ///< [m]
};

/// What a run produced.
struct RunResult {
  std::vector<int> order;  ///< resolved corridor order
  std::vector<RunSample> samples;
  std::vector<CrushRecord> crushes;  ///< every plant crushed, in order
  std::vector<FrameSample> frames;
  std::vector<navigate::NavEvent> events;  ///< odom-frame points
  std::vector<Eigen::Vector2d>
      row_ends_world;  ///< estimated row ends, mapped by the true pose when estimated
  /// One turn frame's row-end point (NavCommand::row_end_points), mapped by the true pose.
  struct TurnRowEnd {
    double stamp = 0.0;  ///< [s] of the command that reported it
    Eigen::Vector2d world = Eigen::Vector2d::Zero();
  };
  std::vector<TurnRowEnd> turn_row_ends_world;  ///< every turn frame's (row_end_points.csv)
  navigate::NavState final_state = navigate::NavState::in_row;
  navigate::StopReason stop_reason = navigate::StopReason::none;
  int turns = 0;
  int served = 0;
  double odometry_alpha = 1.0;     ///< the odometry's alpha at the end (estimated online, or set)
  int odometry_scale_samples = 0;  ///< stretches that measured it (StackConfig::odometry_scale)
  core::Pose2 T_world_odom;        ///< truth of the odom frame (start pose)
  double sim_time = 0.0, wall_time = 0.0;
  std::vector<std::pair<int, int>> entries;  ///< (planned, true corridor) at each entry
  std::vector<PlaceSample> places;           ///< empty: map stage off
  std::vector<KeyLocationSample> key_locations;
};

/// Start pose at the entrance of `order[0]`, facing along it so that the next corridor of the
/// order lies on `first_turn`'s side. Throws std::invalid_argument for a missing corridor.
core::Pose2 mission_start(const sim::FieldTruth& truth, const std::vector<int>& order, int block,
                          navigate::TurnSide first_turn, double lead_in);

/// `start` (mission_start) moved `offset` [m] to its left and turned by `yaw` [rad]: the robot
/// placed off the centre line and yawed.
core::Pose2 perturbed_start(const core::Pose2& start, double offset, double yaw);

/// The stack a run drives with: `setup`'s navigation config, the robot's footprint, limits and
/// odometry model (nav_stack_robot), its detector, tracker and controller.
std::unique_ptr<navigate::NavStack> make_nav_stack(const ClosedLoopSetup& setup,
                                                   const std::vector<int>& order);

/// Runs the mission. Throws std::invalid_argument / InputError for a bad set-up (before
/// simulating); the run itself never throws.
RunResult run_closed_loop(const ClosedLoopSetup& setup);

}  // namespace rownav::io
