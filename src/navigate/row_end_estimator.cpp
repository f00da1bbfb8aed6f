// Row ends and spacing of the corridor being left (navigate/row_end_estimator.hpp).
#include "rownav/navigate/row_end_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "rownav/core/angle.hpp"

namespace rownav::navigate {

Eigen::Vector2d RowEndEstimator::recent_median(std::deque<Eigen::Vector2d>& recent,
                                               const Eigen::Vector2d& p) {
  // The median of a few frames drops single-frame outliers (a weed or post in the headland on
  // the row's line stretches the support).
  recent.push_back(p);
  while (static_cast<int>(recent.size()) > config_.frames) recent.pop_front();
  std::vector<std::pair<double, Eigen::Vector2d>> by_arc;
  for (const auto& q : recent) by_arc.emplace_back(centre_->arc(q), q);
  const auto mid = by_arc.begin() + static_cast<std::ptrdiff_t>(by_arc.size() / 2);
  std::nth_element(by_arc.begin(), mid, by_arc.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  return mid->second;
}

void RowEndEstimator::update(const track::RowTracking& t, const core::Pose2& T,
                             double frame_stamp) {
  if (t.status != track::TrackStatus::tracking) return;
  // Past the row ends only a short stub of row remains behind the robot (and headland clutter
  // ahead): its line is no longer trusted, the exit keeps the last in-row centre line.
  const bool past_end = centre_ && end_arc_ && centre_->arc(T.translation()) > *end_arc_;
  if (!past_end) centre_ = t.centre_line_base.transformed(T);
  if (t.row_spacing > 0.0) {  // running mean of the tracker's spacing (003 Table I row width)
    spacing_ = (spacing_ * spacing_n_ + t.row_spacing) / (spacing_n_ + 1);
    spacing_n_ = std::min(spacing_n_ + 1, config_.spacing_window);
  }
  // Row ends: the far end of the followed rows' support, once it is in view (not range-cut).
  auto end_of = [&](int i) -> std::optional<Eigen::Vector2d> {
    if (i < 0 || i >= static_cast<int>(t.rows.size())) return std::nullopt;
    const auto& r = t.rows[static_cast<std::size_t>(i)];
    if (r.x_max > config_.max_range || r.support < config_.min_support || r.last_seen < frame_stamp)
      return std::nullopt;
    // Only the corridor's own rows end it: past the row ends the tracker may follow clutter
    // across the headland, whose far end is no end of this corridor (issue 11, zoo:7:5 with a
    // 2D scanner: a line 29 deg across pushed the exit on until its budget ran out).
    const Eigen::Vector2d along = T.rotation() * r.line_base.direction;
    if (std::abs(along.dot(centre_->normal())) >
        std::sin(core::deg2rad(config_.row_angle_gate_deg)))
      return std::nullopt;
    return T * Eigen::Vector2d(r.x_max, r.line_base.y_at(r.x_max));
  };
  if (auto e = end_of(t.left)) left_end_ = recent_median(left_ends_, *e);
  if (auto e = end_of(t.right)) right_end_ = recent_median(right_ends_, *e);
  if (left_end_ || right_end_) {
    // The exit clears both rows: the farther end. Rows need not end together (a missing last
    // tree, a shorter row, a gap at one row's end); their mean turned the robot up to half a
    // tree spacing short of the longer row, into its end tree's crown (issue 10, zoo:1:2, 1:27).
    double arc = -std::numeric_limits<double>::infinity();
    for (const auto& e : {left_end_, right_end_})
      if (e) arc = std::max(arc, centre_->arc(*e));
    end_arc_ = arc;
    // Settling: the end point held still (within settle_tolerance) while the robot drove on.
    const Eigen::Vector2d end = centre_->at(*end_arc_);
    robot_ = T.translation();
    if (!anchor_end_ || (end - *anchor_end_).norm() > config_.settle_tolerance) {
      anchor_end_ = end;
      anchor_robot_ = robot_;
    }
  }
}

std::optional<double> RowEndEstimator::settled_end_ahead() const {
  if (!centre_ || !end_arc_ || !anchor_end_) return std::nullopt;
  if ((robot_ - anchor_robot_).norm() < config_.settle_distance) return std::nullopt;
  return *end_arc_ - centre_->arc(robot_);
}

double RowEndEstimator::spacing() const {
  if (spacing_ > 0.0) return spacing_;
  if (left_end_ && right_end_) return (*left_end_ - *right_end_).norm();
  return 0.0;
}

void RowEndEstimator::reset() {
  centre_.reset();
  left_end_.reset();
  right_end_.reset();
  left_ends_.clear();
  right_ends_.clear();
  end_arc_.reset();
  anchor_end_.reset();
}

}  // namespace rownav::navigate
