#pragma once
/// @file bulb_turn.hpp Bulb (omega) turn for car-like robots whose minimum turn radius exceeds
/// half the lateral shift: away from the turn side, a large loop towards it, back into the
/// target corridor. With TurnPlan::can_rotate false the follower backs up along the arc when
/// the look-ahead point falls behind (the three-point choice).
#include "rownav/navigate/turn_planner.hpp"

namespace rownav::navigate {

/// Bulb turn of loop radius TurnGeometry::radius.
class BulbTurn : public TurnPlanner {
 public:
  TurnKind kind() const override { return TurnKind::bulb; }
  std::vector<TurnPrimitive> plan(const TurnGeometry& g) const override;
};

}  // namespace rownav::navigate
