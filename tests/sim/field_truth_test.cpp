#include "rownav/sim/field_truth.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "rownav/sim/robot.hpp"

namespace rownav::sim {
namespace {

/// Four rows along x from 0 to 30 m at y = 0, 2, 4, 6 (plus `amp` sin(x / 8) if curved), a
/// vine every metre.
Field four_rows(double amp = 0.0) {
  Field f;
  f.row_spacing = 2.0;
  f.headland_width = 6.0;
  for (int k = 0; k < 4; ++k) {
    Row r;
    r.id = k;
    for (int i = 0; i <= 60; ++i) {
      const double x = 0.5 * i;
      r.polyline.emplace_back(x, 2.0 * k + amp * std::sin(x / 8.0));
    }
    for (int i = 0; i <= 30; ++i) {
      Plant p;
      p.position = r.polyline[static_cast<std::size_t>(2 * i)];
      p.row = k;
      f.plants.push_back(p);
    }
    Plant post;
    post.kind = PlantKind::post;
    post.position = r.polyline.front() - Eigen::Vector2d(0.5, 0.0);
    f.plants.push_back(post);
    f.rows.push_back(r);
  }
  return f;
}

Place place_at(const FieldTruth& t, double x, double y) {
  return t.at({x, y, 0.0}, 0.0).place;
}

TEST(FieldTruth, PlacesAtKnownPoints) {
  const Field f = four_rows();
  const FieldTruth t(f);
  EXPECT_EQ(t.blocks(), std::vector<int>{0});
  EXPECT_EQ(t.corridor_count(0), 3);
  EXPECT_EQ(t.corridor_count(5), 0);
  for (int k = 0; k < 3; ++k) {
    const GroundTruth g = t.at({15.0, 2.0 * k + 1.0, 0.0}, 0.0);
    EXPECT_EQ(g.place, Place::lane) << k;
    EXPECT_EQ(g.corridor, k);
  }
  EXPECT_EQ(place_at(t, 15.0, -1.0), Place::alley);
  EXPECT_EQ(place_at(t, 15.0, 7.5), Place::alley);
  EXPECT_EQ(place_at(t, 15.0, -2.5), Place::outside);
  EXPECT_EQ(place_at(t, -3.0, 3.0), Place::headland);
  EXPECT_EQ(place_at(t, 33.0, 1.0), Place::headland);
  EXPECT_EQ(place_at(t, 35.0, 9.0), Place::headland);  // headland corner beside the block
  EXPECT_EQ(place_at(t, -7.0, 3.0), Place::outside);
  EXPECT_EQ(place_at(t, 15.0, 20.0), Place::outside);
  const GroundTruth h = t.at({-3.0, 3.0, 0.0}, 0.0);
  EXPECT_EQ(h.corridor, -1);
  ASSERT_TRUE(h.corridor_centre_base.has_value());  // headland next to corridor 1
  EXPECT_NEAR(h.corridor_centre_base->y_at(0.0), 0.0, 1e-9);
}

TEST(FieldTruth, LateralAndHeadingErrorSigns) {
  const Field f = four_rows();
  const FieldTruth t(f);
  GroundTruth g = t.at({10.0, 1.2, 0.1}, 3.0);
  EXPECT_EQ(g.stamp, 3.0);
  EXPECT_NEAR(g.lateral_error, 0.2, 1e-9);  // left of the centre: positive
  EXPECT_NEAR(g.heading_error, 0.1, 1e-9);
  EXPECT_EQ(g.left_row, 1);
  EXPECT_EQ(g.right_row, 0);
  ASSERT_TRUE(g.corridor_centre_base.has_value());
  EXPECT_NEAR(g.corridor_centre_base->y_at(0.0), -0.2 / std::cos(0.1), 1e-9);
  // Driving the other way: left is -y, so the same point is right of the centre.
  g = t.at({10.0, 1.2, M_PI + 0.1}, 0.0);
  EXPECT_NEAR(g.lateral_error, -0.2, 1e-9);
  EXPECT_NEAR(g.heading_error, 0.1, 1e-9);
  EXPECT_EQ(g.left_row, 0);
  EXPECT_EQ(g.right_row, 1);
}

TEST(FieldTruth, RowsInBaseFrameNearestFirst) {
  const Field f = four_rows();
  const FieldTruth t(f);
  const GroundTruth g = t.at({10.0, 1.2, 0.0}, 0.0, 3.0);
  ASSERT_EQ(g.rows.size(), 3u);  // rows at 0.8, 1.2 and 2.8 m
  EXPECT_EQ(g.rows[0].row, 1);
  EXPECT_NEAR(g.rows[0].lateral, 0.8, 1e-9);
  EXPECT_EQ(g.rows[1].row, 0);
  EXPECT_NEAR(g.rows[1].lateral, -1.2, 1e-9);
  EXPECT_NEAR(g.rows[1].line_base.y_at(0.0), -1.2, 1e-9);
  EXPECT_NEAR(g.rows[1].start_base.x(), -10.0, 1e-9);
  EXPECT_NEAR(g.rows[1].end_base.x(), 20.0, 1e-9);
  EXPECT_EQ(g.rows[2].row, 2);
}

TEST(FieldTruth, CurvedRowsFollowTheCentre) {
  const double amp = 1.5;
  const Field f = four_rows(amp);
  const FieldTruth t(f);
  const auto& c = t.corridor_centre(0, 1);
  ASSERT_GT(c.size(), 100u);
  for (double x : {4.0, 12.5, 21.0}) {
    const double y = 3.0 + amp * std::sin(x / 8.0);
    const double heading = std::atan(amp / 8.0 * std::cos(x / 8.0));
    const GroundTruth g = t.at({x, y, heading}, 0.0);
    EXPECT_EQ(g.place, Place::lane);
    EXPECT_EQ(g.corridor, 1);
    EXPECT_NEAR(g.lateral_error, 0.0, 0.01) << x;
    EXPECT_NEAR(g.heading_error, 0.0, 0.01) << x;
    const GroundTruth off = t.at({x, y + 0.3, heading}, 0.0);
    EXPECT_NEAR(off.lateral_error, 0.3 * std::cos(heading), 0.02) << x;
  }
}

TEST(FieldTruth, NaNPoseGivesOutside) {
  const Field f = four_rows();
  const FieldTruth t(f);
  EXPECT_EQ(t.at({std::nan(""), 1.0, 0.0}, 0.0).place, Place::outside);
}

std::array<Eigen::Vector2d, 4> footprint(const core::Pose2& T) {
  Robot r(RobotConfig{}, 1, T);
  return r.footprint_world();
}

TEST(CrushCounter, CentreLineCrushesNothingRowCrushesOnce) {
  const Field f = four_rows();
  CrushCounter cc(f);
  for (double x = -2.0; x <= 32.0; x += 0.05) EXPECT_EQ(cc.update(footprint({x, 3.0, 0.0})), 0);
  EXPECT_EQ(cc.total(), 0);
  // Over row 1 from x = 5 to 10: the 0.9 m footprint (+ 5 cm plant radius) reaches vines 5..10.
  int sum = 0;
  for (double x = 5.0; x <= 10.0 + 1e-9; x += 0.05) sum += cc.update(footprint({x, 2.0, 0.0}));
  EXPECT_EQ(sum, 6);
  EXPECT_EQ(cc.total(), 6);
  for (double x = 10.0; x >= 5.0; x -= 0.05) cc.update(footprint({x, 2.0, M_PI}));
  EXPECT_EQ(cc.total(), 6);  // once per plant
  // Posts are not plants.
  cc.update(footprint({-0.5, 0.0, 0.0}));
  for (int i : cc.crushed_indices())
    EXPECT_NE(f.plants[static_cast<std::size_t>(i)].kind, PlantKind::post);
}

}  // namespace
}  // namespace rownav::sim
