#pragma once
/// @file turn_path.hpp Path geometry of the headland turns (turn frame): arcs, joined paths, the
/// re-anchoring weight along a path and the resampling the pursuit cursor needs.
#include <Eigen/Core>
#include <vector>

namespace rownav::navigate {

/// [m] spacing of the points of a turn path (arcs, resampled legs).
inline constexpr double kTurnPathStep = 0.1;

/// Points of an arc around c from a to b (same radius), counter-clockwise when ccw, every
/// kTurnPathStep.
std::vector<Eigen::Vector2d> turn_arc(const Eigen::Vector2d& c, const Eigen::Vector2d& a,
                                      const Eigen::Vector2d& b, bool ccw);

/// Appends `more` to `path`, skipping a point that repeats the last one.
void append_path(std::vector<Eigen::Vector2d>& path, const std::vector<Eigen::Vector2d>& more);

/// Weight of the target correction along a path: its cumulative length fraction (0 to 1).
std::vector<double> anchor_ramp(const std::vector<Eigen::Vector2d>& path);

/// Resamples a path every kTurnPathStep, with its anchor weights, so the cursor can advance.
void densify_turn_path(std::vector<Eigen::Vector2d>& path, std::vector<double>& w);

}  // namespace rownav::navigate
