// Malavazi 2018's data filter (core/data_filter.hpp): boxes around the followed models, the
// 0.3-3 m window on a side without one.
#include "rownav/core/data_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace rownav::core {
namespace {

TEST(DataFilter, KeepsOnlyPointsInsideTheBoxesAroundTheModels) {
  DataFilterBoxes f;
  f.models[0] = SideModel{0.0, 0.5};    // left row y = 0.5
  f.models[1] = SideModel{0.1, -0.5};   // right row y = 0.1 x - 0.5
  f.half_width = 0.1;
  const std::vector<Eigen::Vector2f> pts = {
      {1.0f, 0.55f},   // left box
      {1.0f, 0.0f},    // a weed in the lane
      {2.0f, -0.31f},  // right box (0.1 * 2 - 0.5 = -0.3)
      {2.0f, -0.5f},   // 0.2 from the right model: out
      {1.0f, 0.75f}};  // beyond the left box
  const auto kept = filter_points(pts, f);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_FLOAT_EQ(kept[0].y(), 0.55f);
  EXPECT_FLOAT_EQ(kept[1].y(), -0.31f);
}

// The paper's window (Malavazi 2018 sec. 3.1.1), as track::ModelFilterConfig gives it.
DataFilterBoxes paper_windows() {
  DataFilterBoxes f;
  f.init_min_range = 0.3;
  f.init_max_range = 3.0;
  return f;
}

TEST(DataFilter, SideWithoutModelKeepsItsPointsThirtyCentimetresToThreeMetresAway) {
  const DataFilterBoxes f = paper_windows();  // no model on either side: sec. 3.1.1 windows
  const std::vector<Eigen::Vector2f> pts = {
      {0.1f, 0.1f}, {1.0f, 0.4f}, {2.0f, -1.0f}, {3.5f, 0.2f}, {0.0f, -0.29f}};
  const auto kept = filter_points(pts, f);
  ASSERT_EQ(kept.size(), 2u);  // 0.14 m and 3.5 m and 0.29 m are out
  EXPECT_FLOAT_EQ(kept[0].x(), 1.0f);
  EXPECT_FLOAT_EQ(kept[1].x(), 2.0f);
}

TEST(DataFilter, OneModelOneWindow) {
  DataFilterBoxes f = paper_windows();
  f.models[0] = SideModel{0.0, 0.4};
  f.half_width = 0.05;
  const std::vector<Eigen::Vector2f> pts = {{1.0f, 0.2f}, {1.0f, 0.42f}, {1.0f, -0.6f}};
  const auto kept = filter_points(pts, f);  // left: box only; right: its window
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_FLOAT_EQ(kept[0].y(), 0.42f);
  EXPECT_FLOAT_EQ(kept[1].y(), -0.6f);
}

TEST(DataFilter, NonFinitePointsAreDropped) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<Eigen::Vector2f> pts = {{nan, 0.5f}, {1.0f, inf}, {1.0f, 0.5f}};
  EXPECT_EQ(filter_points(pts, paper_windows()).size(), 1u);
}

TEST(DataFilter, RandomWeedsBetweenRowsNeverReachTheFit) {
  // Seeded property: rows at +-s/2, weeds uniformly in the lane's middle; with the models known
  // and the box a fifth of the spacing, every weed more than half_width from a row is removed.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int trial = 0; trial < 50; ++trial) {
    const float s = 0.6f + 2.4f * u(rng);
    DataFilterBoxes f;
    f.models[0] = SideModel{0.0, 0.5 * s};
    f.models[1] = SideModel{0.0, -0.5 * s};
    f.half_width = 0.2 * s;
    std::vector<Eigen::Vector2f> weeds;
    for (int i = 0; i < 100; ++i) weeds.push_back({4.0f * u(rng), 0.55f * s * (u(rng) - 0.5f)});
    EXPECT_TRUE(filter_points(weeds, f).empty()) << "spacing " << s;
  }
}

}  // namespace
}  // namespace rownav::core
