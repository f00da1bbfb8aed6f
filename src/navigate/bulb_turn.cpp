// Bulb turn (navigate/bulb_turn.hpp).
#include "rownav/navigate/bulb_turn.hpp"

#include <algorithm>
#include <cmath>

#include "rownav/navigate/turn_path.hpp"

namespace rownav::navigate {

std::vector<TurnPrimitive> BulbTurn::plan(const TurnGeometry& g) const {
  // Three tangent circles: away from the side, the loop of radius r, back into the corridor.
  const double e = g.exit_x, r = g.radius, s = g.side, D = g.shift * g.spacing;
  const Eigen::Vector2d c1(e, -s * r), c3(e, s * (D + r));
  const double h = std::sqrt(std::max(0.0, 4.0 * r * r - std::pow(D / 2.0 + r, 2)));
  const Eigen::Vector2d c2(e + h, s * D / 2.0);
  const Eigen::Vector2d t12 = (c1 + c2) / 2.0, t23 = (c2 + c3) / 2.0;
  const bool ccw = g.side > 0;
  TurnPrimitive p;
  append_path(p.path, turn_arc(c1, {e, 0.0}, t12, !ccw));
  append_path(p.path, turn_arc(c2, t12, t23, ccw));
  append_path(p.path, turn_arc(c3, t23, {e, s * D}, !ccw));
  p.anchor = anchor_ramp(p.path);
  return {p};
}

}  // namespace rownav::navigate
