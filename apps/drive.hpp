#pragma once
/// @file drive.hpp A scripted drive: the simulator's pure-pursuit driver follows a path while
/// every sensor stream goes to a sink (usually a recording).
#include <Eigen/Core>
#include <vector>

#include "rownav/sim/scripted_path.hpp"
#include "rownav/sim/simulator.hpp"

namespace rownav::app {

/// What a scripted drive did.
struct DriveSummary {
  double sim_time = 0.0;    ///< [s] simulated
  double wall_time = 0.0;   ///< [s] spent
  bool completed = false;   ///< reached the end of the path
  int lidar_frames = 0;     ///< sweeps / scans produced
  int plants_crushed = 0;
  double lane_rms_lateral = 0.0;  ///< [m] RMS distance to the corridor centre while in a lane
  double lane_max_lateral = 0.0;  ///< [m]
  std::vector<Eigen::Vector2d> trajectory;  ///< true positions, one per ground-truth sample
  sim::GroundTruth middle_truth;            ///< truth at the sweep nearest the middle of the drive
};

/// Runs the drive until the path ends or `max_time` elapses; shows progress on stderr.
DriveSummary run_scripted_drive(sim::Simulator& sim, sim::PathFollower& driver,
                                sim::SimSink& sink, double max_time, bool progress);

}  // namespace rownav::app
