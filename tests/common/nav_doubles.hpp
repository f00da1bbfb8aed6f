#pragma once
// Test doubles for the navigation stack: a pass-through row tracker and a proportional
// heading + lateral controller. They stand in for the real trackers / controllers in the
// navigator and closed-loop tests (and, temporarily, in the CLI: apps/temp_nav_doubles.hpp).
#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>

#include "rownav/control/controller.hpp"
#include "rownav/core/row_observation.hpp"
#include "rownav/track/row_tracker.hpp"

namespace rownav::test {

/// Turns RowObservation::corridor into RowTracking; through gaps it carries the last corridor
/// centre line by odometry (coasting), lost after `max_coast` seconds.
class PassThroughTracker : public track::RowTracker {
 public:
  explicit PassThroughTracker(double max_coast = 1.0) : max_coast_(max_coast) {}
  std::string_view name() const override { return "pass_through"; }
  void reset() override { last_.reset(); }

  track::RowTracking update(const core::RowObservation& obs, const core::Pose2& T) override {
    track::RowTracking t;
    t.stamp = obs.stamp;
    if (obs.corridor) {
      const auto& c = *obs.corridor;
      t.centre_line_base = core::Line2({0.0, c.offset}, {std::cos(c.heading), std::sin(c.heading)});
      t.row_spacing = c.width;
      spacing_ = c.width > 0.0 ? c.width : spacing_;
      for (std::size_t i = 0; i < obs.rows.size(); ++i) {
        const auto& r = obs.rows[i];
        t.rows.push_back({static_cast<int>(i), r.line, r.offset, r.heading, r.x_min, r.x_max,
                          r.support, 0.0, obs.stamp});
      }
      t.left = obs.left;
      t.right = obs.right;
      t.status = track::TrackStatus::tracking;
      t.confidence = obs.confidence;
      last_ = {obs.stamp, t.centre_line_base.transformed(T)};
    } else if (last_ && obs.stamp - last_->stamp <= max_coast_) {
      t.centre_line_base = last_->centre_odom.transformed(T.inverse());
      t.row_spacing = spacing_;
      t.status = track::TrackStatus::coasting;
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

 private:
  struct Last {
    double stamp;
    core::Line2 centre_odom;
  };
  double max_coast_;
  double spacing_ = 0.0;
  std::optional<Last> last_;
};

/// omega = -k_lat * lateral_error - k_head * heading_error, v = speed_ref (slower near obstacles).
class ProportionalController : public control::PathController {
 public:
  ProportionalController(double k_lat = 1.0, double k_head = 1.5)
      : k_lat_(k_lat), k_head_(k_head) {}
  std::string_view name() const override { return "proportional"; }
  void reset() override {}
  core::Twist2 compute(const control::ControlInput& in) override {
    if (!std::isfinite(in.lateral_error) || !std::isfinite(in.heading_error)) return {};
    const double w = -k_lat_ * in.lateral_error - k_head_ * in.heading_error;
    double v = in.speed_ref;
    if (std::isfinite(in.obstacle_distance)) v *= std::clamp(in.obstacle_distance / 2.0, 0.0, 1.0);
    return {v, 0.0, std::clamp(w, -1.0, 1.0)};
  }

 private:
  double k_lat_, k_head_;
};

}  // namespace rownav::test
