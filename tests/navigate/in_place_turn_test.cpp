#include "rownav/navigate/in_place_turn.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace rownav::navigate {
namespace {

TEST(InPlaceTurn, RotatesAQuarterTurnDrivesTheHeadlandLegAndRotatesIntoTheTarget) {
  for (int side : {1, -1})
    for (int shift : {1, 2, 3}) {
      const TurnGeometry g{1.2, shift, side, 1.8, 0.0};
      const auto p = InPlaceTurn().plan(g);
      ASSERT_EQ(p.size(), 3u);
      EXPECT_TRUE(p[0].rotate);
      EXPECT_DOUBLE_EQ(p[0].heading, side * std::numbers::pi / 2.0);
      ASSERT_FALSE(p[1].rotate);
      EXPECT_TRUE(p[1].headland);  // the leg along the row ends, counting rows (003 II-C)
      ASSERT_EQ(p[1].path.size(), 2u);
      EXPECT_EQ(p[1].path.front(), Eigen::Vector2d(1.2, 0.0));
      EXPECT_NEAR(p[1].path.back().y(), side * shift * 1.8, 1e-12);
      EXPECT_DOUBLE_EQ(p[1].path.back().x(), 1.2);  // parallel to the row-end line
      EXPECT_EQ(p[1].anchor, (std::vector<double>{0.0, 1.0}));
      EXPECT_TRUE(p[2].rotate);
      EXPECT_DOUBLE_EQ(p[2].heading, std::numbers::pi);  // back along -x, into the corridor
      EXPECT_EQ(make_turn_planner(TurnKind::in_place)->kind(), TurnKind::in_place);
    }
}

}  // namespace
}  // namespace rownav::navigate
