#include "rownav/track/tracker_base.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rownav::track {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// An observation worth correcting with: rows and a finite stamp.
bool usable(const core::RowObservation& obs) {
  return obs.status != core::DetectionStatus::no_rows && !obs.rows.empty();
}

}  // namespace

void TrackerConfig::validate() const {
  core::check_positive(max_coast_time, "max_coast_time");
  core::check_positive(max_speed, "max_speed");
  core::check_positive(max_yaw_rate_deg, "max_yaw_rate_deg");
  core::check_positive(default_row_spacing, "default_row_spacing");
  core::check_range(spacing_window, 1, 100000, "spacing_window");
  core::check_range(gap_width_ratio, 0.0, 10.0, "gap_width_ratio");
  core::check_range(settle_frames, 0, 100000, "settle_frames");
  core::check_range(width_tolerance, 0.0, 1.0, "width_tolerance");
  core::check(std::isfinite(target_offset), "target_offset", "must be finite");
}

TrackerBase::TrackerBase(const TrackerConfig& common)
    : common_((common.validate(), common)), spacing_(common.spacing_window) {}

void TrackerBase::reset() {
  clear_models();
  started_ = false;
  last_ = RowTracking{};
  spacing_.reset();
  width_ = 0.0;
  width_frames_ = 0;
}

RowTracking TrackerBase::update(const core::RowObservation& obs, const core::Pose2& T_odom_base) {
  if (!std::isfinite(obs.stamp) || !finite(T_odom_base)) return last_;
  if (started_ && obs.stamp <= last_stamp_) return last_;  // stale or time going backwards
  if (started_) {
    const double dt = obs.stamp - last_stamp_;
    const core::Pose2 step = last_pose_.inverse() * T_odom_base;
    // An odometry jump (reset, wrong fusion) is not applied: the models stay where they were in
    // the base frame and the next observation corrects them.
    const bool jump = step.translation().norm() > common_.max_speed * dt + 0.05 ||
                      std::abs(step.theta) > common_.max_yaw_rate_deg * kDeg * dt + 0.02;
    if (dt > common_.max_coast_time) clear_models();
    if (has_model()) predict(jump ? core::Pose2() : step, T_odom_base, dt);
  }
  started_ = true;
  last_stamp_ = obs.stamp;
  last_pose_ = T_odom_base;
  RowTracking out;
  out.stamp = obs.stamp;
  if (usable(obs) && correct(obs, T_odom_base)) {
    if (!sees_past_a_gap(obs)) spacing_.add(obs);
    last_seen_ = obs.stamp;
    out.status = TrackStatus::tracking;
  } else if (has_model() && obs.stamp - last_seen_ <= common_.max_coast_time) {
    out.status = TrackStatus::coasting;
  } else {
    clear_models();
    out.status = TrackStatus::lost;
  }
  out.time_since_observation = has_model() ? obs.stamp - last_seen_ : 0.0;
  if (has_model()) {
    describe(out);
    follow_nearer_past_a_gap(out);
    fill_centres(out);
    fill_deviations(out);
  }
  if (out.left < 0 && out.right < 0) out.status = TrackStatus::lost;
  if (out.status != TrackStatus::lost) {
    const double fresh = 1.0 - out.time_since_observation / common_.max_coast_time;
    const double sides = (out.left >= 0 && out.right >= 0) ? 1.0 : 0.6;
    const double det =
        out.status == TrackStatus::tracking ? std::clamp(obs.confidence, 0.3, 1.0) : 1.0;
    out.confidence = std::clamp(fresh * sides * det, 0.0, 1.0);
  }
  finish(out);
  last_ = out;
  return out;
}

bool TrackerBase::wider_than_corridor(const core::Line2& left, const core::Line2& right) const {
  const double spacing = spacing_.spacing();
  if (width_frames_ < common_.settle_frames || !(width_ > 0.0) || !(spacing > 0.0)) return false;
  const double w = spacing_between(left, right);
  return std::isfinite(w) && w - width_ > common_.gap_width_ratio * spacing;
}

bool TrackerBase::sees_past_a_gap(const core::RowObservation& obs) const {
  // Only a frame with two rows is ambiguous: with more, robust_spacing counts a difference that
  // spans a missing row as two against the frame's other differences.
  const int n = static_cast<int>(obs.rows.size());
  if (n != 2 || obs.left < 0 || obs.right < 0 || obs.left >= n || obs.right >= n) return false;
  return wider_than_corridor(obs.rows[static_cast<std::size_t>(obs.left)].line,
                             obs.rows[static_cast<std::size_t>(obs.right)].line);
}

void TrackerBase::follow_nearer_past_a_gap(RowTracking& out) {
  if (out.left < 0 || out.right < 0) return;
  const TrackedRow& l = out.rows[static_cast<std::size_t>(out.left)];
  const TrackedRow& r = out.rows[static_cast<std::size_t>(out.right)];
  if (!wider_than_corridor(l.line_base, r.line_base)) return;
  // The followed row that went missing was replaced by the row beyond it: the farther one.
  const bool left = std::abs(l.offset) > std::abs(r.offset);
  (left ? out.left : out.right) = -1;
  forget_side(left);
}

void TrackerBase::update_width(const RowTracking& out, double width) {
  const double w = std::max(width, 0.0);
  // A width that moved breaks the settled corridor; one that held counts only when both rows
  // were seen in this frame (models coasting through a gap keep whatever width they had).
  const bool seen = out.rows[static_cast<std::size_t>(out.left)].last_seen >= out.stamp &&
                    out.rows[static_cast<std::size_t>(out.right)].last_seen >= out.stamp;
  const bool held = width_ > 0.0 && std::abs(w - width_) <= common_.width_tolerance * width_;
  if (!held) width_frames_ = 0;
  if (held && seen) ++width_frames_;
  width_ = w;
}

void TrackerBase::fill_centres(RowTracking& out) const {
  if (!(out.row_spacing > 0.0)) out.row_spacing = spacing_.spacing();
  for (std::size_t i = 0; i < out.rows.size(); ++i) {
    TrackedRow& r = out.rows[i];
    if (std::isfinite(r.centre_offset)) continue;
    const bool followed = static_cast<int>(i) == out.left || static_cast<int>(i) == out.right;
    const bool left = r.offset >= 0.0;
    const double c = std::max(std::abs(r.line_base.direction.x()), 1e-3);
    r.centre_offset = r.offset + (followed ? (left ? 1.0 : -1.0) * spacing_.shift(left) / c : 0.0);
    if (followed) r.half_width = spacing_.half_width(left);
  }
}

void TrackerBase::fill_deviations(RowTracking& out) {
  const bool has_l = out.left >= 0, has_r = out.right >= 0;
  if (!has_l && !has_r) return;
  const auto row = [&](int i) { return out.rows[static_cast<std::size_t>(i)].line_base; };
  // A single row's corridor centre lies half the corridor width from its fitted line: the last
  // width measured between the followed lines, else the spacing less the canopy (issue 10: the
  // spacing is centre to centre, the lines are the corridor-side faces of opaque canopies).
  if (has_l && has_r) update_width(out, spacing_between(row(out.left), row(out.right)));
  const TrackedRow& one = out.rows[static_cast<std::size_t>(has_l ? out.left : out.right)];
  const double spacing = out.row_spacing > 0.0 ? out.row_spacing : common_.default_row_spacing;
  const double canopy = std::abs(one.centre_offset - one.offset);
  out.corridor_width = width_ > 0.0             ? width_
                       : spacing > 2.0 * canopy ? spacing - 2.0 * canopy
                                                : spacing;
  const double single = out.corridor_width;
  out.centre_line_base = has_l && has_r ? centre_between(row(out.left), row(out.right))
                         : has_l        ? centre_from_one(row(out.left), true, single)
                                        : centre_from_one(row(out.right), false, single);
  const Deviation d = deviation(out.centre_line_base);
  out.lateral_error = d.lateral;
  out.heading_error = d.heading;
  double slope = 0.0;
  int n = 0;
  for (const int i : {out.left, out.right})
    if (i >= 0) slope += std::abs(slope_intercept(row(i)).a), ++n;
  out.steepness = slope / n;
  const int target = common_.target_row == TargetRow::left    ? out.left
                     : common_.target_row == TargetRow::right ? out.right
                                                              : -1;
  if (target >= 0) {  // signed distance of the base from the target row, minus the wanted one
    const core::Line2 t = row(target);
    out.target_lateral_error = t.signed_distance(Eigen::Vector2d::Zero()) - common_.target_offset;
  }
}

}  // namespace rownav::track
