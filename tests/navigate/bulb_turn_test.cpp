#include "rownav/navigate/bulb_turn.hpp"

#include <gtest/gtest.h>

#include "turn_path_checks.hpp"

namespace rownav::navigate {
namespace {

TEST(BulbTurn, ALoopNoTighterThanTheRobotsRadiusWhenTheShiftIsTooSmallForAUTurn) {
  for (int side : {1, -1})
    for (double r : {1.5, 2.5, 4.0}) {
      const TurnGeometry g{1.2, 1, side, 1.8, r};  // 1.8 m shift < 2 r: no U-turn fits
      const auto p = BulbTurn().plan(g);
      ASSERT_EQ(p.size(), 1u);
      test::expect_followable(p[0], g, r);
      // It first swings away from the turn side (the omega's first arc).
      double away = 0.0;
      for (const auto& q : p[0].path) away = std::max(away, -side * q.y());
      EXPECT_GT(away, 0.05) << r;
    }
  EXPECT_EQ(make_turn_planner(TurnKind::bulb)->kind(), TurnKind::bulb);
}

}  // namespace
}  // namespace rownav::navigate
