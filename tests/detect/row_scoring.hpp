#pragma once
// Scoring of a RowObservation against known row lines (tests only).
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "rownav/core/row_observation.hpp"

namespace rownav::test {

/// Errors of the detected row nearest to a truth line, at x.
struct LineScore {
  bool found = false;
  double lateral = std::numeric_limits<double>::infinity();  ///< [m] |y_det(x) - y_true(x)|
  double heading_deg = 180.0;                                ///< [deg]
};

inline double y_at(const core::Line2& l, double x) {
  return l.y_at(x);
}

/// The detected row closest to `truth` at x (within `gate` [m]).
inline LineScore score_line(const core::RowObservation& obs, const core::Line2& truth, double x,
                            double gate = 0.3) {
  LineScore s;
  for (const auto& r : obs.rows) {
    const double d = std::abs(r.line.y_at(x) - truth.y_at(x));
    if (d > gate || d >= s.lateral) continue;
    s.found = true;
    s.lateral = d;
    const double dh =
        std::abs(std::remainder(r.line.heading() - truth.heading(), std::numbers::pi));
    s.heading_deg = dh * 180.0 / std::numbers::pi;
  }
  return s;
}

/// Worst of the two truth rows around the robot (the middle two of a symmetric scene).
struct CorridorScore {
  int found = 0;
  double lateral = 0.0;      ///< [m] worst
  double heading_deg = 0.0;  ///< [deg] worst
};

inline CorridorScore score_corridor(const core::RowObservation& obs,
                                    const std::vector<core::Line2>& truth, double x) {
  CorridorScore c;
  int right = -1, left = -1;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const double y = truth[k].y_at(x);
    if (y < 0.0) right = static_cast<int>(k);
    if (y >= 0.0 && left < 0) left = static_cast<int>(k);
  }
  for (const int k : {right, left}) {
    if (k < 0) continue;
    const LineScore s = score_line(obs, truth[static_cast<std::size_t>(k)], x);
    c.found += s.found ? 1 : 0;
    c.lateral = std::max(c.lateral, s.lateral);
    c.heading_deg = std::max(c.heading_deg, s.heading_deg);
  }
  return c;
}

}  // namespace rownav::test
