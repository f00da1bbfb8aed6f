#pragma once
/// @file turn_planner.hpp One headland turn kind = one planner behind one interface (as
/// Fields2Cover keeps one file per turn type): a planner lays out the primitives of its turn in
/// the turn frame (origin on the exit corridor's centre line at the row ends, x along the exit
/// direction, y to the left); navigate::HeadlandManoeuvre drives them on the odometry pose.
/// Kinds: navigate/in_place_turn.hpp, navigate/u_turn.hpp, navigate/bulb_turn.hpp; the skip-row
/// mission is a U-turn over k > 1 corridors and the three-point choice a bulb whose car-like
/// robot backs up (TurnPlan::can_rotate = false).
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "rownav/navigate/turn_choice.hpp"

namespace rownav::navigate {

/// One piece of a turn: a rotation in place to a heading, or a path to follow.
struct TurnPrimitive {
  bool rotate = false;
  double heading = 0.0;               ///< [rad] rotate: target heading (turn frame)
  std::vector<Eigen::Vector2d> path;  ///< [m] follow: points (turn frame)
  /// [0-1] follow: how much of the target's re-anchoring shift applies at each point (0 at the
  /// exit, 1 in the target corridor)
  std::vector<double> anchor;
  bool headland = false;  ///< the leg along the row ends (003: counting rows)
};

/// Where a turn goes.
struct TurnGeometry {
  double exit_x = 0.0;  ///< [m] x at which the turn starts (exit distance past the row ends)
  int shift = 1;        ///< [corridors] across, >= 1
  int side = 1;         ///< +1 left, -1 right
  double spacing = 1.0;  ///< [m] row spacing (centre to centre)
  double radius = 0.0;   ///< [m] arcs (TurnPlan::radius)
  /// [m] planned target corridor centre (turn y) = side * shift * spacing
  double target_y() const { return side * shift * spacing; }
};

/// A turn kind's planner. Pure: plan() depends on its arguments only; never throws.
class TurnPlanner {
 public:
  virtual ~TurnPlanner() = default;
  virtual TurnKind kind() const = 0;
  virtual std::vector<TurnPrimitive> plan(const TurnGeometry& g) const = 0;
};

/// The planner of `kind`.
std::unique_ptr<TurnPlanner> make_turn_planner(TurnKind kind);

}  // namespace rownav::navigate
