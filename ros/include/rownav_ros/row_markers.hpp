#pragma once
/// @file row_markers.hpp The tracked rows and the corridor as RViz markers (issue 15: "the
/// tracked rows and corridor as visualization_msgs/MarkerArray"), in the base frame.
#include <ros/time.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>

#include "rownav/track/row_tracker.hpp"

namespace rownav::ros_bridge {

/// Marker sizes and reach.
struct RowMarkerStyle {
  double line_width = 0.05;      ///< [m] row lines
  double corridor_ahead = 5.0;   ///< [m] corridor centre line drawn from x = 0 to this far ahead
  double lifetime = 0.5;         ///< [s] a marker not refreshed disappears (frames stop)
};

/// One DELETEALL (the previous frame's rows go) then, in `frame` at `stamp`: a line strip per
/// tracked row over its supported extent (x_min..x_max; the followed left / right rows green,
/// the others grey; namespace "rows", id = the row's index), and the corridor centre line
/// (blue, namespace "corridor") when the tracker has one (status not lost).
visualization_msgs::MarkerArray row_markers(const track::RowTracking& tracking,
                                            const std::string& frame, const ros::Time& stamp,
                                            const RowMarkerStyle& style = {});

}  // namespace rownav::ros_bridge
