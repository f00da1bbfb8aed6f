#include <gtest/gtest.h>

#include <numbers>

#include "rownav/core/line2.hpp"
#include "rownav/core/pose2.hpp"

namespace rownav::core {
namespace {

TEST(Pose2, ComposeWithInverseIsIdentity) {
  const Pose2 T_a_b(1.5, -2.0, 0.7);
  const Pose2 I = T_a_b * T_a_b.inverse();
  EXPECT_NEAR(I.x, 0.0, 1e-12);
  EXPECT_NEAR(I.y, 0.0, 1e-12);
  EXPECT_NEAR(I.theta, 0.0, 1e-12);
}

TEST(Pose2, TransformsPointsLeftOfHeading) {
  const Pose2 T_world_base(2.0, 1.0, std::numbers::pi / 2);
  const Eigen::Vector2d p = T_world_base * Eigen::Vector2d(1.0, 0.0);
  EXPECT_NEAR(p.x(), 2.0, 1e-12);
  EXPECT_NEAR(p.y(), 2.0, 1e-12);
}

TEST(Pose2, WrapsHeadingAndInterpolatesShortestArc) {
  const Pose2 a(0, 0, deg2rad(170)), b(0, 0, deg2rad(-170));
  EXPECT_NEAR(rad2deg(interpolate(a, b, 0.5).theta), 180.0, 1e-9);
  EXPECT_NEAR(Pose2(0, 0, 3 * std::numbers::pi).theta, std::numbers::pi, 1e-12);
}

TEST(Line2, SignedDistanceIsPositiveOnTheLeft) {
  const Line2 l = Line2::from_slope_intercept(0.0, 1.0);
  EXPECT_NEAR(l.signed_distance({3.0, 2.5}), 1.5, 1e-12);
  EXPECT_NEAR(l.signed_distance({3.0, 0.0}), -1.0, 1e-12);
  EXPECT_NEAR(l.y_at(5.0), 1.0, 1e-12);
}

TEST(Line2, TransformMatchesPointTransform) {
  const Line2 l_b = Line2::through({0, 1}, {2, 1.5});
  const Pose2 T_a_b(1.0, -1.0, 0.3);
  const Line2 l_a = l_b.transformed(T_a_b);
  EXPECT_NEAR(l_a.signed_distance(T_a_b * Eigen::Vector2d(4.0, 2.0)), 0.0, 1e-12);
  EXPECT_NEAR(angle_diff(l_a.heading(), l_b.heading()), 0.3, 1e-12);
}

TEST(Segment2, DistanceClampsToEnds) {
  const Segment2 s{{0, 0}, {2, 0}};
  EXPECT_NEAR(s.distance({1, 1}), 1.0, 1e-12);
  EXPECT_NEAR(s.distance({3, 0}), 1.0, 1e-12);
}

}  // namespace
}  // namespace rownav::core
