// The planner of each turn kind (navigate/turn_planner.hpp).
#include "rownav/navigate/turn_planner.hpp"

#include "rownav/navigate/bulb_turn.hpp"
#include "rownav/navigate/in_place_turn.hpp"
#include "rownav/navigate/u_turn.hpp"

namespace rownav::navigate {

std::unique_ptr<TurnPlanner> make_turn_planner(TurnKind kind) {
  switch (kind) {
    case TurnKind::in_place:
      return std::make_unique<InPlaceTurn>();
    case TurnKind::u_turn:
      return std::make_unique<UTurn>();
    case TurnKind::bulb:
      break;
  }
  return std::make_unique<BulbTurn>();
}

}  // namespace rownav::navigate
