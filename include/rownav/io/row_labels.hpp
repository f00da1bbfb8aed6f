#pragma once
/// @file row_labels.hpp Hand-labelled row lines of a 2D LiDAR data set, e.g.
/// `../shared/data/corn_rows_2d/labels.csv`: columns
/// `frame,left_x0,left_y0,left_x1,left_y1,right_x0,right_y0,right_x1,right_y1` (metres, sensor
/// frame, x forward, y left; point 0 is the nearer one; `left` has the larger y).
#include <cstdint>
#include <filesystem>
#include <map>

#include "rownav/core/line2.hpp"

namespace rownav::io {

/// The two labelled rows of one frame, each as the segment between the clicked points.
struct RowLabel {
  core::Segment2 left;
  core::Segment2 right;
};

/// Labels by frame number. InputError "file:line: reason" on malformed content.
std::map<std::int64_t, RowLabel> read_row_labels(const std::filesystem::path& file);

}  // namespace rownav::io
