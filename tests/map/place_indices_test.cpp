// Instantaneous indices and state per place (Emmi 2021 eq. (4)-(9)).
#include "rownav/map/place_indices.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "map/map_scene.hpp"

namespace rownav::map {
namespace {

PlaceIndices indices_at(const test::SynthScene& s, const core::Pose2& T, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  LabelledClusters c;
  const auto f = test::scan(s, T, rng);
  c.add(f.points, f.labels, T);
  return compute_place_indices(c.update(T), T, 0.5, {}, KeyLocationConfig{},
                               PlaceIndicesConfig{});
}

TEST(PlaceIndices, BetweenTwoRowsIsALane) {
  test::SynthScene s;
  s.rows = test::block(3, 1.0, 0.0, 20.0);
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const PlaceIndices i = indices_at(s, core::Pose2(10.0, 1.5, 0.05), seed);
    EXPECT_EQ(i.instantaneous, Place::lane);
    EXPECT_LT(i.cluster_idx, 0.1);
    EXPECT_GT(i.c_index[1], 0.85);
  }
}

TEST(PlaceIndices, BesideTheOuterRowIsAnAlley) {
  test::SynthScene s;
  s.rows = test::block(3, 1.0, 0.0, 20.0);
  const PlaceIndices i = indices_at(s, core::Pose2(10.0, 3.5, 0.0), 7);
  EXPECT_EQ(i.instantaneous, Place::alley);
  EXPECT_TRUE(i.right_beside);
  EXPECT_FALSE(i.left_beside);
}

TEST(PlaceIndices, BeyondTheRowEndsIsTheHeadland) {
  test::SynthScene s;
  s.rows = test::block(3, 1.0, 0.0, 20.0);
  // Facing the rows from 1.5 m before them, and driving along the headland across them.
  EXPECT_EQ(indices_at(s, core::Pose2(-1.5, 1.5, 0.0), 8).instantaneous, Place::headland);
  EXPECT_EQ(indices_at(s, core::Pose2(-1.0, 1.2, std::numbers::pi / 2), 9).instantaneous,
            Place::headland);
}

TEST(PlaceIndices, ANeighbouringFieldOfAnotherCropIsNotALane) {
  test::SynthScene s;
  s.rows = test::block(2, 1.0, 0.0, 20.0);
  // Another crop's rows 1 m left of the last row: the robot between them is in the alley.
  for (auto& r : test::block(2, 1.0, 0.0, 20.0, PointLabel::other_crop, 3.0)) s.rows.push_back(r);
  const PlaceIndices i = indices_at(s, core::Pose2(10.0, 2.5, 0.0), 10);
  EXPECT_EQ(i.instantaneous, Place::alley);
}

TEST(PlaceIndices, ClusterIndexIsZeroAlongARowAndOneAcrossIt) {
  RowCluster row;
  row.line = core::Line2({0.0, 0.5}, {1.0, 0.0});
  row.arc_min = -5.0;
  row.arc_max = 5.0;
  EXPECT_NEAR(cluster_index(row, core::Pose2(0.0, 0.0, 0.0), 1.0), 0.0, 1e-9);
  EXPECT_GT(cluster_index(row, core::Pose2(6.0, 0.0, 0.0), 1.0), 0.4);  // past the row end
  EXPECT_NEAR(cluster_index(row, core::Pose2(0.0, -1.0, std::numbers::pi / 2), 1.0), 1.0, 1e-9);
}

TEST(PlaceIndices, NoClearMaximumIsUnknown) {
  EXPECT_EQ(instantaneous_place({0.49, 0.46, 0.05}, 0.05), Place::unknown);
  EXPECT_EQ(instantaneous_place({0.40, 0.55, 0.05}, 0.05), Place::lane);
}

TEST(PlaceIndices, PositionCorrelationOfCollinearKeyLocationsIsOne) {
  EXPECT_NEAR(position_correlation({{0, 0}, {1, 1}, {2, 2.0}}), 1.0, 1e-9);
  EXPECT_LT(position_correlation({{0, 0}, {1, 1}, {2, 0}, {1, -1}}), 0.1);
  EXPECT_EQ(position_correlation({{0, 0}, {1, 1}}), 0.0);
}

}  // namespace
}  // namespace rownav::map
