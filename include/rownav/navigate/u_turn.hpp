#pragma once
/// @file u_turn.hpp Lan 2021 (001_b5f4b55a1b95775a.txt sec. 3.3): a fixed-radius turn, radius
/// spacing / 2, into the adjacent corridor; generalised to arc - straight - arc when the shift
/// exceeds twice the radius (skip-row missions, car-like robots with a larger radius).
#include "rownav/navigate/turn_planner.hpp"

namespace rownav::navigate {

/// U-turn of radius TurnGeometry::radius.
class UTurn : public TurnPlanner {
 public:
  TurnKind kind() const override { return TurnKind::u_turn; }
  std::vector<TurnPrimitive> plan(const TurnGeometry& g) const override;
};

}  // namespace rownav::navigate
