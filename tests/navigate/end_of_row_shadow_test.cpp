// The planar end of row's shadow test against what a voxel grid leaves of a 2D scan: the ground
// across the lane where the scan plane pitches into a bump, scattered weeds, and the followed
// rows' own canopy beside the box (issue 11).
#include <gtest/gtest.h>

#include <vector>

#include "rownav/navigate/end_of_row.hpp"

namespace rownav::navigate {
namespace {

constexpr double kVoxel = 0.15;  // [m] the vineyard detection config's voxel edge

// Rows followed on both sides, their inner faces at y = +-face (planar fits: no centre line),
// seen up to x_max; spacing as a tracker reports it.
track::RowTracking followed(double face, double x_max, double spacing) {
  track::RowTracking t;
  t.status = track::TrackStatus::tracking;
  for (const double y : {-face, face}) {
    track::TrackedRow r;
    r.offset = y;
    r.x_min = 0.3;
    r.x_max = x_max;
    t.rows.push_back(r);
  }
  t.right = 0;
  t.left = 1;
  t.row_spacing = spacing;
  return t;
}

// Voxel centroids of two rows' faces at y = +-face from x = 0.3 to x_end, one per cell.
std::vector<Eigen::Vector2f> faces(double face, double x_end) {
  std::vector<Eigen::Vector2f> pts;
  for (double x = 0.3; x < x_end; x += kVoxel)
    for (const double y : {-face, face}) pts.emplace_back(float(x), float(y));
  return pts;
}

EndOfRowConfig planar_config(double link) {
  EndOfRowConfig c;  // box 3-5 m, 1 deg bins, shadow_wall 0.5: the vineyard defaults
  c.shadow_link = link;
  return c;
}

bool declared_after(EndOfRowDetector& d, const std::vector<Eigen::Vector2f>& pts,
                    const track::RowTracking& t, int frames) {
  EndOfRowResult r;
  for (int k = 0; k < frames; ++k) r = d.update(core::PointCloud{}, pts, t);
  return r.end_detected;
}

TEST(EndOfRowShadow, TheGroundAcrossTheLaneAtABumpHidesTheBoxBetweenItsVoxelCentroids) {
  // The plane dips into the ground 2.3 m ahead: one centroid per 0.15 m cell across the lane,
  // nothing beyond; the rows are seen up to the same line. Taken as open ground, the empty box
  // ended 4 of 8 random zoo vineyards' first row at a bump (issue 11).
  const double face = 0.8;
  auto pts = faces(face, 2.4);
  for (double y = -face + 0.05; y < face; y += kVoxel)
    pts.emplace_back(float(2.3 + 0.04 * y), float(y));  // a slightly skewed line
  const auto t = followed(face, 2.4, 2.2);
  EndOfRowDetector unlinked(planar_config(0.0)), linked(planar_config(2.0 * kVoxel));
  const int frames = 2 * EndOfRowConfig{}.confirm_frames;
  EXPECT_TRUE(declared_after(unlinked, pts, t, frames));  // the gaps read as open ground
  EXPECT_FALSE(declared_after(linked, pts, t, frames));
}

TEST(EndOfRowShadow, ScatteredWeedsBeforeTheBoxDoNotHideARowEnd) {
  // The rows end 2.4 m ahead; six single weeds in the lane, each farther than the link from the
  // next, hide a few bins only: the box is seen empty, the end is declared.
  const double face = 0.8;
  auto pts = faces(face, 2.4);
  for (int i = 0; i < 6; ++i) pts.emplace_back(float(1.2 + 0.3 * i), float(-0.6 + 0.25 * i));
  EndOfRowDetector d(planar_config(2.0 * kVoxel));
  EXPECT_TRUE(
      declared_after(d, pts, followed(face, 2.4, 2.2), 2 * EndOfRowConfig{}.confirm_frames));
}

TEST(EndOfRowShadow, TheFollowedRowsOwnCanopyBesideTheBoxIsNoOccluder) {
  // Thick rows (inner faces at +-0.6 m, canopy to +-1.3 m) end 2.8 m ahead. Over the box's half
  // width (spacing / 2 + row_margin = 1.55 m) their returns shadow more than half the bearings;
  // over the lane between the followed faces, none: the end is declared.
  const double face = 0.6;
  std::vector<Eigen::Vector2f> pts;
  for (double x = 0.3; x < 2.8; x += kVoxel)
    for (double y = face; y < 1.3; y += kVoxel)
      for (const double side : {-1.0, 1.0}) pts.emplace_back(float(x), float(side * y));
  const int frames = 2 * EndOfRowConfig{}.confirm_frames;
  EndOfRowDetector with_rows(planar_config(2.0 * kVoxel)), without(planar_config(2.0 * kVoxel));
  EXPECT_TRUE(declared_after(with_rows, pts, followed(face, 2.8, 2.1), frames));
  // Not knowing the followed rows, the whole box's half width is the lane: unseen.
  track::RowTracking unknown = followed(face, 2.8, 2.1);
  unknown.left = unknown.right = -1;
  EXPECT_FALSE(declared_after(without, pts, unknown, frames));
}

}  // namespace
}  // namespace rownav::navigate
