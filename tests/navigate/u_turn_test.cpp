#include "rownav/navigate/u_turn.hpp"

#include <gtest/gtest.h>

#include "turn_path_checks.hpp"

namespace rownav::navigate {
namespace {

TEST(UTurn, ASemicircleOfHalfTheSpacingIntoTheNextCorridor) {
  for (int side : {1, -1}) {
    const TurnGeometry g{1.2, 1, side, 1.8, 0.9};
    const auto p = UTurn().plan(g);
    ASSERT_EQ(p.size(), 1u);
    test::expect_followable(p[0], g, 0.9);
    for (const auto& q : p[0].path)  // Lan 2021: every point on the circle of radius spacing / 2
      EXPECT_NEAR((q - Eigen::Vector2d(1.2, side * 0.9)).norm(), 0.9, 1e-9);
  }
}

TEST(UTurn, ArcStraightArcWhenTheShiftExceedsTwiceTheRadius) {
  for (int side : {1, -1})
    for (int shift : {2, 3}) {
      const TurnGeometry g{1.0, shift, side, 1.8, 1.0};
      const auto p = UTurn().plan(g);
      ASSERT_EQ(p.size(), 1u);
      test::expect_followable(p[0], g, 1.0);
      double x_max = 0.0;
      for (const auto& q : p[0].path) x_max = std::max(x_max, q.x());
      EXPECT_NEAR(x_max, 1.0 + 1.0, 1e-9);  // the straight leg runs one radius into the headland
    }
  EXPECT_EQ(make_turn_planner(TurnKind::u_turn)->kind(), TurnKind::u_turn);
}

}  // namespace
}  // namespace rownav::navigate
