// In-place turn + headland leg (navigate/in_place_turn.hpp).
#include "rownav/navigate/in_place_turn.hpp"

#include <numbers>

namespace rownav::navigate {

std::vector<TurnPrimitive> InPlaceTurn::plan(const TurnGeometry& g) const {
  constexpr double pi = std::numbers::pi;
  // Bertoglio 2023 sec. II-B/C: rotate 90 deg, drive along the row ends, rotate 90 deg.
  TurnPrimitive first{true, g.side * pi / 2.0, {}, {}, false};
  TurnPrimitive leg;
  leg.path = {{g.exit_x, 0.0}, {g.exit_x, g.target_y()}};
  leg.anchor = {0.0, 1.0};  // the stop in the target corridor follows its re-anchored centre
  leg.headland = true;
  TurnPrimitive last{true, pi, {}, {}, false};
  return {first, leg, last};
}

}  // namespace rownav::navigate
