#include "rownav/navigate/swept_box.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rownav::navigate {
namespace {

TEST(SweptBox, StraightIsTheBoxAhead) {
  EXPECT_TRUE(in_swept_box({0.7, 0.2}, 0.0, 0.45, 0.95, 0.3));
  EXPECT_FALSE(in_swept_box({0.7, 0.4}, 0.0, 0.45, 0.95, 0.3));  // beside
  EXPECT_FALSE(in_swept_box({1.2, 0.0}, 0.0, 0.45, 0.95, 0.3));  // beyond
  EXPECT_FALSE(in_swept_box({0.2, 0.0}, 0.0, 0.45, 0.95, 0.3));  // inside the footprint
}

TEST(SweptBox, FollowsTheArcOfALeftTurn) {
  // Radius 2 m to the left: the point 0.7 m along the arc lies left of the straight box, and
  // a post straight ahead at 0.9 m lies outside the arc's box.
  const double k = 0.5, R = 2.0, s = 0.7;
  const Eigen::Vector2d on_arc(R * std::sin(s / R), R * (1.0 - std::cos(s / R)));
  EXPECT_TRUE(in_swept_box(on_arc, k, 0.45, 0.95, 0.1));
  const Eigen::Vector2d ahead(0.95, -0.05);
  EXPECT_TRUE(in_swept_box(ahead, 0.0, 0.45, 1.0, 0.1));
  EXPECT_FALSE(in_swept_box(ahead, k, 0.45, 1.0, 0.1));
}

TEST(SweptBox, RightTurnsMirrorLeftTurns) {
  const double R = 3.0, s = 0.8;
  const Eigen::Vector2d left(R * std::sin(s / R), R * (1.0 - std::cos(s / R)));
  const Eigen::Vector2d right(left.x(), -left.y());
  EXPECT_TRUE(in_swept_box(left, 1.0 / R, 0.45, 0.95, 0.05));
  EXPECT_TRUE(in_swept_box(right, -1.0 / R, 0.45, 0.95, 0.05));
  EXPECT_FALSE(in_swept_box(right, 1.0 / R, 0.45, 0.95, 0.05));
}

TEST(SweptBox, PointsBehindAndNonFiniteAreOutside) {
  EXPECT_FALSE(in_swept_box({-0.7, 0.0}, 0.5, 0.45, 0.95, 0.3));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(in_swept_box({nan, 0.0}, 0.5, 0.45, 0.95, 0.3));
  EXPECT_FALSE(in_swept_box({0.7, 0.0}, nan, 0.45, 0.95, 0.3));
}

}  // namespace
}  // namespace rownav::navigate
