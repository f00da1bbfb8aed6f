#pragma once
/// @file corridor_frame.hpp Test helper: a navigator frame in a straight corridor along odom x.
#include "rownav/navigate/navigator.hpp"

namespace rownav::navigate::testing {

/// The robot at odom x = `x` heading +x; rows at +-0.9 m (1.8 m apart) tracked from odom x `from`
/// to `to` (their base-frame extents follow). `seen`: the detector saw the rows this frame and
/// the tracker updated them; otherwise it coasts on them (last seen at 0).
inline NavInput corridor_frame(double t, double x, double from, double to, bool seen) {
  NavInput in;
  in.stamp = t;
  in.T_odom_base = core::Pose2(x, 0.0, 0.0);
  in.observation.status = seen ? core::DetectionStatus::ok : core::DetectionStatus::no_rows;
  in.observation.stamp = t;
  if (seen) in.observation.corridor = core::CorridorObservation{0.0, 0.0, 1.8};
  in.tracking.status = seen ? track::TrackStatus::tracking : track::TrackStatus::coasting;
  in.tracking.row_spacing = 1.8;
  in.tracking.centre_line_base = core::Line2({0.0, 0.0}, {1.0, 0.0});
  for (const double y : {-0.9, 0.9}) {
    track::TrackedRow r;
    r.line_base = core::Line2({0.0, y}, {1.0, 0.0});
    r.offset = y;
    r.x_min = from - x;
    r.x_max = to - x;
    r.support = 40;
    r.last_seen = seen ? t : 0.0;
    in.tracking.rows.push_back(r);
  }
  in.tracking.right = 0, in.tracking.left = 1;
  return in;
}

}  // namespace rownav::navigate::testing
