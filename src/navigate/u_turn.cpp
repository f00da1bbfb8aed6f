// U-turn (navigate/u_turn.hpp).
#include "rownav/navigate/u_turn.hpp"

#include "rownav/navigate/turn_path.hpp"

namespace rownav::navigate {

std::vector<TurnPrimitive> UTurn::plan(const TurnGeometry& g) const {
  // Lan 2021: semicircle of radius spacing / 2 for k = 1; arc - straight - arc for k > 1.
  const double e = g.exit_x, r = g.radius, s = g.side, D = g.shift * g.spacing;
  const bool ccw = g.side > 0;
  TurnPrimitive p;
  if (D <= 2.0 * r + 1e-9) {
    const Eigen::Vector2d c(e, s * D / 2.0);
    p.path = turn_arc(c, {e, 0.0}, {e, s * D}, ccw);
  } else {
    append_path(p.path, turn_arc({e, s * r}, {e, 0.0}, {e + r, s * r}, ccw));
    append_path(p.path, {{e + r, s * (D - r)}});
    append_path(p.path, turn_arc({e, s * (D - r)}, {e + r, s * (D - r)}, {e, s * D}, ccw));
  }
  p.anchor = anchor_ramp(p.path);
  return {p};
}

}  // namespace rownav::navigate
