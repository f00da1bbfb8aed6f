#include "rownav/track/raw_corridor.hpp"

#include <cmath>
#include <vector>

#include "rownav/track/row_geometry.hpp"

namespace rownav::track {

void RawCorridorConfig::validate() const { core::check_positive(max_coast_time, "max_coast_time"); }

RawCorridorTracker::RawCorridorTracker(const RawCorridorConfig& config) : config_(config) {
  config_.validate();
}

RowTracking RawCorridorTracker::update(const core::RowObservation& obs, const core::Pose2& T) {
  RowTracking t;
  t.stamp = obs.stamp;
  const bool usable = obs.corridor && std::isfinite(obs.corridor->offset) &&
                      std::isfinite(obs.corridor->heading);
  if (usable) {
    const auto& c = *obs.corridor;
    t.centre_line_base = core::Line2({0.0, c.offset}, {std::cos(c.heading), std::sin(c.heading)});
    // The corridor width is face to face for an opaque canopy: the spacing is centre to centre
    // over every row seen (issue 10), the last one kept while a frame has fewer than two rows.
    t.corridor_width = c.width;
    std::vector<double> centres;
    for (std::size_t i = 0; i < obs.rows.size(); ++i) {
      const auto& r = obs.rows[i];
      t.rows.push_back({static_cast<int>(i), r.line, r.offset, r.heading, r.x_min, r.x_max,
                        r.support, 0.0, obs.stamp, core::centre_offset(r), r.half_width});
      centres.push_back(core::centre_offset(r));
    }
    if (const double s = robust_spacing(std::move(centres)); s > 0.0) spacing_ = s;
    t.row_spacing = spacing_;
    t.left = obs.left;
    t.right = obs.right;
    t.status = TrackStatus::tracking;
    t.confidence = obs.confidence;
    last_ = Last{obs.stamp, t.centre_line_base.transformed(T)};
  } else if (last_ && obs.stamp >= last_->stamp &&
             obs.stamp - last_->stamp <= config_.max_coast_time) {
    t.centre_line_base = last_->centre_odom.transformed(T.inverse());
    t.row_spacing = spacing_;
    t.status = TrackStatus::coasting;
    t.confidence = 0.5;
  } else {
    return t;  // lost
  }
  if (t.centre_line_base.direction.x() < 0.0)
    t.centre_line_base.direction = -t.centre_line_base.direction;
  t.lateral_error = -t.centre_line_base.y_at(0.0);
  t.heading_error = -t.centre_line_base.heading();
  t.time_since_observation = last_ ? obs.stamp - last_->stamp : 0.0;
  return t;
}

}  // namespace rownav::track
