#pragma once
// Properties every followed turn path must have (u_turn_test, bulb_turn_test).
#include <gtest/gtest.h>

#include <cmath>

#include "rownav/navigate/turn_path.hpp"
#include "rownav/navigate/turn_planner.hpp"

namespace rownav::navigate::test {

/// Starts on the exit centre line at the exit x, ends on the target centre line at the exit x,
/// stays in the headland (x >= exit x), is sampled every kTurnPathStep at most once resampled as
/// the manoeuvre does, the anchor weight grows from 0 to 1, and no three consecutive points bend
/// tighter than `min_radius`.
inline void expect_followable(TurnPrimitive p, const TurnGeometry& g, double min_radius) {
  densify_turn_path(p.path, p.anchor);
  ASSERT_FALSE(p.rotate);
  ASSERT_GE(p.path.size(), 3u);
  ASSERT_EQ(p.anchor.size(), p.path.size());
  EXPECT_LT((p.path.front() - Eigen::Vector2d(g.exit_x, 0.0)).norm(), 1e-9);
  EXPECT_LT((p.path.back() - Eigen::Vector2d(g.exit_x, g.target_y())).norm(), 1e-6);
  EXPECT_DOUBLE_EQ(p.anchor.front(), 0.0);
  EXPECT_DOUBLE_EQ(p.anchor.back(), 1.0);
  for (std::size_t i = 1; i < p.path.size(); ++i) {
    EXPECT_GE(p.path[i].x(), g.exit_x - 1e-9) << i;
    EXPECT_LE((p.path[i] - p.path[i - 1]).norm(), kTurnPathStep + 1e-9) << i;
    EXPECT_GE(p.anchor[i], p.anchor[i - 1]) << i;
  }
  for (std::size_t i = 1; i + 1 < p.path.size(); ++i) {
    const Eigen::Vector2d a = p.path[i - 1], b = p.path[i], c = p.path[i + 1];
    const double cross = std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
    if (cross < 1e-12) continue;  // straight
    // Circumradius of the three points.
    const double R = (b - a).norm() * (c - b).norm() * (c - a).norm() / (2.0 * cross);
    EXPECT_GE(R, 0.98 * min_radius) << i;
  }
}

}  // namespace rownav::navigate::test
