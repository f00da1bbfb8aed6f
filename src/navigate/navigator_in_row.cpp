// Navigator in a row: following, the lane check, the row end (the end-of-row detector, or rows
// lost just before their settled end) and the start of the exit.
#include <algorithm>
#include <cmath>
#include <span>

#include "rownav/navigate/navigator.hpp"

namespace rownav::navigate {

namespace {

/// The robot is at the rows unless every followed row is seen to begin farther than `reach`
/// ahead of the base (a tracking without row extents cannot tell: at the rows).
bool reached_rows(const track::RowTracking& t, double reach) {
  if (t.status == track::TrackStatus::lost) return false;
  bool any = false;
  for (const int i : {t.left, t.right}) {
    if (i < 0 || i >= static_cast<int>(t.rows.size())) continue;
    const double x = t.rows[static_cast<std::size_t>(i)].x_min;
    if (!std::isfinite(x) || x <= reach) return true;
    any = true;
  }
  return !any;
}

/// Whether a followed row goes on past x = from (base frame): the returns within `across` of
/// its line span more than `length` along it beyond from (a ridge or a weed that hid the rows
/// leaves them there; clutter across the headland crosses the line in a point or two). Without a
/// followed row: true.
bool row_goes_on(const track::RowTracking& t, std::span<const Eigen::Vector2f> pts, double from,
                 double across, double length) {
  bool any = false;
  for (const int i : {t.left, t.right}) {
    if (i < 0 || i >= static_cast<int>(t.rows.size())) continue;
    any = true;
    const core::Line2& line = t.rows[static_cast<std::size_t>(i)].line_base;
    double lo = 1e300, hi = -1e300;
    for (const auto& p : pts) {
      const Eigen::Vector2d q = p.cast<double>();
      if (q.x() <= from || std::abs(line.signed_distance(q)) > across) continue;
      lo = std::min(lo, q.x()), hi = std::max(hi, q.x());
    }
    if (hi - lo > length) return true;
  }
  return !any;  // no followed row left to look along: cannot tell, it may go on
}

/// [m] free width between the followed rows' inner canopy edges; nullopt without both rows.
std::optional<double> clear_width(const track::RowTracking& t) {
  const auto f = track::inner_faces(t);
  if (!f) return std::nullopt;
  const double w = f->left_face - f->right_face;
  return std::isfinite(w) ? std::optional<double>(w) : std::nullopt;
}

}  // namespace

void Navigator::check_lane(const NavInput& in, NavOutput& out) {
  if (config_.narrow_frames == 0 || narrow_said_ ||
      in.tracking.status != track::TrackStatus::tracking)
    return;
  const auto w = clear_width(in.tracking);
  if (!w) return;
  ++lane_frames_;
  if (*w < in.robot.width + 2.0 * config_.narrow_margin) ++narrow_count_;
  // Most of the corridor's frames so far, and at least narrow_frames of them (a gap or a
  // wrong frame is not a narrow corridor).
  if (narrow_count_ < config_.narrow_frames || 2 * narrow_count_ <= lane_frames_) return;
  narrow_said_ = true;
  out.events.push_back({in.stamp, NavEventKind::narrow_corridor, order_[leg_],
                        in.T_odom_base.translation(),
                        "lane " + fmt(*w) + " m clear between the rows' canopies, robot " +
                            fmt(in.robot.width) + " m wide: it will brush or crush plants"});
}

std::string Navigator::fmt(double v) {  // event texts: centimetres are enough
  std::ostringstream s;
  s.precision(2);
  s << std::fixed << v;
  return s.str();
}
void Navigator::in_row(const NavInput& in, NavOutput& out) {
  // A sweep whose rays passed over the rows' band (end_of_row.blind: a small robot pitched up on
  // a bump) is no sign that the rows are gone: while the tracker carries them by odometry
  // (coasting, bounded by its max_coast_time) the perception timer does not run (issue 10: zoo
  // leek fields stopped perception_lost after 0.6 s of such sweeps).
  const bool blind_coasting =
      in.sweep_3d && in.end_of_row.blind && in.tracking.status == track::TrackStatus::coasting;
  const bool seen = blind_coasting || (in.observation.status != core::DetectionStatus::no_rows &&
                                       in.tracking.status != track::TrackStatus::lost);
  if (seen) last_seen_ = in.stamp;
  if (in.stamp - last_seen_ > config_.perception_timeout) {
    // Rows lost just before the end they were seen to have (standing still in odom) while the
    // lane ahead is in view: the detector ran out of row, a planar one with a few metres left
    // (issue 11), not a blind robot. Leave the row as at a detected end. A ridge or a weed
    // also stands still in odom, but hides the lane (end-of-row shadow test), and rows that go
    // on leave their returns beyond it.
    const auto ahead = ends_.settled_end_ahead();
    const auto& settle = config_.row_end_estimate;
    if (at_rows_ && in.end_of_row.box_seen && ahead && *ahead <= config_.lost_rows_end_reach &&
        !row_goes_on(in.tracking, in.points_base, *ahead + settle.settle_tolerance,
                     settle.settle_tolerance, settle.settle_distance)) {
      start_exit(in, out, "rows lost " + fmt(*ahead) + " m before their settled end");
      return exiting(in.T_odom_base, out, in.stamp);
    }
    return stop(StopReason::perception_lost, out, in.stamp,
                "no rows for " + fmt(in.stamp - last_seen_) + " s" +
                    (in.points_base.empty()
                         ? " and no points in the detection window (sensor above the crop, "
                           "or pointed away from it?)"
                         : ""));
  }
  if (const auto obstacle = obstacle_ahead(in))
    return stop(StopReason::obstacle, out, in.stamp, *obstacle);
  if (const auto blocked = held_by_obstacle(in))
    return stop(StopReason::obstacle, out, in.stamp, *blocked);
  ends_.update(in.tracking, in.T_odom_base, in.observation.stamp);
  check_lane(in, out);
  control::ControlInput c;
  c.stamp = in.stamp;
  c.lateral_error = in.tracking.lateral_error;
  c.heading_error = in.tracking.heading_error;
  c.path_base = in.tracking.centre_line_base;
  c.steepness = in.tracking.steepness;
  c.speed_ref = config_.row_speed;
  c.speed = in.twist.v;
  out.control = c;
  const auto& centre = ends_.centre();
  at_rows_ = at_rows_ || reached_rows(in.tracking, config_.arm_reach);
  // Before the rows (a start in the headland) the end-of-row box sees the rows' first plants
  // only: that is no row end, and the detector latches what it declares, so its evidence starts
  // at the rows (issue 10: leek fields of the zoo latched a row end 1.5 m before the first plant
  // and drove out by odometry at once).
  if (!at_rows_) out.reset_end_of_row = true;
  if (in.end_of_row.end_detected && centre && at_rows_) start_exit(in, out, "row end detected");
}

void Navigator::start_exit(const NavInput& in, NavOutput& out, const std::string& why) {
  const core::Line2& centre = *ends_.centre();
  state_ = NavState::exiting;
  blocked_since_.reset();
  exit_distance_ = exit_distance(in);
  if (!ends_.end_arc()) {  // no row end seen: the detector's distance, else the box's near edge
    const double ahead = in.end_of_row.distance_to_end.value_or(end_box_near_);
    ends_.set_end_arc(centre.arc(in.T_odom_base.translation()) + ahead);
  }
  const double end = *ends_.end_arc();
  declared_end_ = centre.at(end);
  const double left = end - centre.arc(in.T_odom_base.translation()) + exit_distance_;
  exit_effort_ = StateEffort{std::max(0.0, left), std::max(0.0, left) / config_.row_speed};
  out.events.push_back(
      {in.stamp, NavEventKind::row_end, order_[leg_], centre.at(end),
       why + ", " + fmt(end - centre.arc(in.T_odom_base.translation())) + " m ahead"});
}

double Navigator::exit_distance(const NavInput& in) const {
  double canopy = 0.0;  // widest measured half width of the followed rows
  for (const int i : {in.tracking.left, in.tracking.right}) {
    if (i < 0 || i >= static_cast<int>(in.tracking.rows.size())) continue;
    const double h = in.tracking.rows[static_cast<std::size_t>(i)].half_width;
    if (std::isfinite(h)) canopy = std::max(canopy, h);
  }
  return std::max(config_.exit_distance, canopy + 0.5 * in.robot.width + config_.exit_clearance);
}

}  // namespace rownav::navigate
