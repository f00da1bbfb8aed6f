// The tracked rows and corridor as RViz markers (rownav_ros/row_markers.hpp).
#include "rownav_ros/row_markers.hpp"

#include <gtest/gtest.h>

namespace {

using rownav::ros_bridge::row_markers;
using visualization_msgs::Marker;

rownav::track::TrackedRow row(double offset, double x_min, double x_max) {
  rownav::track::TrackedRow r;
  r.offset = offset;
  r.line_base = rownav::core::Line2({0.0, offset}, {1.0, 0.1});
  r.x_min = x_min, r.x_max = x_max;
  return r;
}

TEST(RowMarkers, ClearThenOneLinePerRowOverItsExtentAndTheCorridor) {
  rownav::track::RowTracking t;
  t.status = rownav::track::TrackStatus::tracking;
  t.rows = {row(-2.7, 0.0, 6.0), row(-0.9, -1.0, 8.0), row(0.9, -1.0, 7.5)};
  t.right = 1, t.left = 2;
  t.centre_line_base = rownav::core::Line2({0.0, 0.05}, {1.0, 0.0});
  const auto a = row_markers(t, "base_link", ros::Time(12.5));
  ASSERT_EQ(a.markers.size(), 5u);
  EXPECT_EQ(a.markers[0].action, Marker::DELETEALL);
  for (std::size_t i = 1; i < 4; ++i) {
    const Marker& m = a.markers[i];
    EXPECT_EQ(m.ns, "rows");
    EXPECT_EQ(m.header.frame_id, "base_link");
    EXPECT_DOUBLE_EQ(m.header.stamp.toSec(), 12.5);
    ASSERT_EQ(m.points.size(), 2u);
    const auto& r = t.rows[i - 1];
    EXPECT_NEAR(m.points[0].x, r.x_min, 1e-9);
    EXPECT_NEAR(m.points[1].x, r.x_max, 1e-9);
    EXPECT_NEAR(m.points[1].y, r.offset + 0.1 * r.x_max, 1e-9);  // along the row's heading
  }
  // Followed rows stand out from the others.
  EXPECT_GT(a.markers[2].color.g, a.markers[1].color.g);
  EXPECT_GT(a.markers[3].color.g, a.markers[1].color.g);
  EXPECT_EQ(a.markers[4].ns, "corridor");
  EXPECT_NEAR(a.markers[4].points[0].y, 0.05, 1e-9);
}

TEST(RowMarkers, LostTrackingDrawsNoCorridorAndEmptyExtentsNoRow) {
  rownav::track::RowTracking t;
  t.status = rownav::track::TrackStatus::lost;
  t.rows = {row(1.0, 2.0, 2.0)};
  const auto a = row_markers(t, "base_link", ros::Time(1.0));
  ASSERT_EQ(a.markers.size(), 1u);
  EXPECT_EQ(a.markers[0].action, Marker::DELETEALL);
}

}  // namespace
