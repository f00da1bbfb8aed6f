// Turn choice (navigate/turn_choice.hpp).
#include "rownav/navigate/turn_choice.hpp"

#include <algorithm>
#include <cmath>

namespace rownav::navigate {

namespace {

constexpr double kRadiusMargin = 1.25;  // [-] turn radius / min turn radius (car-like robots)

}  // namespace

int min_feasible_shift(double spacing, double min_turn_radius) {
  if (!(spacing > 0.0) || !(min_turn_radius > 0.0)) return 1;
  return std::max(1, static_cast<int>(
                        std::ceil(2.0 * kRadiusMargin * min_turn_radius / spacing - 1e-9)));
}

TurnPlan choose_turn(ManoeuvreChoice choice, int shift, double spacing, const TurnAbility& robot) {
  const double lateral = std::max(1, shift) * spacing;
  const bool in_place_ok = robot.can_turn_in_place;
  if ((choice == ManoeuvreChoice::automatic || choice == ManoeuvreChoice::in_place) && in_place_ok)
    return {TurnKind::in_place, 0.0, true};
  // Lan 2021 (001 sec. 3.3): fixed radius = spacing / 2; never below the robot's minimum.
  // A car-like robot gets kRadiusMargin x its minimum: its steering takes ~1 s to swing from
  // lock to lock between the arcs, and it needs curvature to spare to come back onto the path.
  const double r = std::max(spacing / 2.0, kRadiusMargin * robot.min_turn_radius);
  if (choice != ManoeuvreChoice::three_point && lateral >= 2.0 * r - 1e-9)
    return {TurnKind::u_turn, r, in_place_ok};
  return {TurnKind::bulb, r, in_place_ok};
}

}  // namespace rownav::navigate
