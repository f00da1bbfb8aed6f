#pragma once
/// @file in_place_turn.hpp Bertoglio 2023 (003_25dc0df51a1e5faf.txt sec. II-B/C): rotate 90 deg
/// in place, drive parallel to the row-end line while counting the row ends passed, stop in the
/// middle of the target corridor, rotate 90 deg into it.
#include "rownav/navigate/turn_planner.hpp"

namespace rownav::navigate {

/// In-place turn + headland leg (robots that turn in place: skid steer, differential).
class InPlaceTurn : public TurnPlanner {
 public:
  TurnKind kind() const override { return TurnKind::in_place; }
  std::vector<TurnPrimitive> plan(const TurnGeometry& g) const override;
};

}  // namespace rownav::navigate
