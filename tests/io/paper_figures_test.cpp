// The published Malavazi 2018 figures printed beside rownav's bench tables.
#include "rownav/io/paper_figures.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rownav::io {
namespace {

TEST(PaperFigures, MalavaziTablesAsPrinted) {
  // Table 1 RUBY filtered; Table 2 RANSAC filtered; Table 3 PEARL only (no success: NaN error).
  const auto ruby = malavazi_2018_figures(1, "ruby", true);
  ASSERT_TRUE(ruby);
  EXPECT_DOUBLE_EQ(ruby->success, 100.0);
  EXPECT_DOUBLE_EQ(ruby->ratio_mean, 1.15);
  const auto ransac = malavazi_2018_figures(2, "ransac_lines", true);
  ASSERT_TRUE(ransac);
  EXPECT_DOUBLE_EQ(ransac->success, 50.0);
  EXPECT_DOUBLE_EQ(ransac->success_no_crush, 20.0);
  const auto pearl = malavazi_2018_figures(3, "pearl", false);
  ASSERT_TRUE(pearl);
  EXPECT_DOUBLE_EQ(pearl->success, 0.0);
  EXPECT_TRUE(std::isnan(pearl->ratio_mean));
  EXPECT_FALSE(malavazi_2018_figures(4, "ruby", true));
  EXPECT_FALSE(malavazi_2018_figures(1, "hough_skew", true));
}

TEST(PaperFigures, WeedLevelFromTheFieldName) {
  EXPECT_EQ(weed_level_of("market_garden_weeds_none"), 1);
  EXPECT_EQ(weed_level_of("vineyard_weeds_some"), 2);
  EXPECT_EQ(weed_level_of("vineyard_weeds_many"), 3);
  EXPECT_FALSE(weed_level_of("vineyard_narrow"));
  EXPECT_FALSE(weed_level_of("weeds_many_plot"));
}

}  // namespace
}  // namespace rownav::io
