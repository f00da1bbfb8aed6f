// Navigator in a row: following, the lane check, the row end (the end-of-row detector, or rows
// lost just before their settled end) and the start of the exit.
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

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

/// The x of this frame's returns beyond x = from (base frame) within `across` of a row's line.
void returns_along(const track::TrackedRow& row, std::span<const Eigen::Vector2f> pts, double from,
                   double across, std::vector<double>& xs) {
  xs.clear();
  for (const auto& p : pts) {
    const Eigen::Vector2d q = p.cast<double>();
    if (q.x() > from && std::abs(row.line_base.signed_distance(q)) <= across) xs.push_back(q.x());
  }
}

/// Whether a followed row goes on past x = from (base frame): the returns within `across` of
/// its line span more than `length` along it beyond from (a ridge or a weed that hid the rows
/// leaves them there; clutter across the headland crosses the line in a point or two). Without a
/// followed row: true.
bool row_goes_on(const track::RowTracking& t, std::span<const Eigen::Vector2f> pts, double from,
                 double across, double length) {
  bool any = false;
  std::vector<double> xs;
  for (const int i : {t.left, t.right}) {
    if (i < 0 || i >= static_cast<int>(t.rows.size())) continue;
    any = true;
    returns_along(t.rows[static_cast<std::size_t>(i)], pts, from, across, xs);
    const auto [lo, hi] = std::minmax_element(xs.begin(), xs.end());
    if (lo != xs.end() && *hi - *lo > length) return true;
  }
  return !any;  // no followed row left to look along: cannot tell, it may go on
}

/// Whether a followed row's returns beyond x = from (base frame), within `across` of its line,
/// fill more than `length` of it, counted in bins `across` long: a row that runs on. A few
/// returns of one ring on a bump stretch a row model's extent as far as a row would, but fill
/// one or two bins (zoo:1:11). Without a followed row: false.
bool row_runs_on(const track::RowTracking& t, std::span<const Eigen::Vector2f> pts, double from,
                 double across, double length) {
  std::vector<double> xs;
  for (const int i : {t.left, t.right}) {
    if (i < 0 || i >= static_cast<int>(t.rows.size())) continue;
    returns_along(t.rows[static_cast<std::size_t>(i)], pts, from, across, xs);
    for (double& x : xs) x = std::floor((x - from) / across);  // the bin of each return
    std::sort(xs.begin(), xs.end());
    const auto filled = std::unique(xs.begin(), xs.end()) - xs.begin();
    if (double(filled) * across > length) return true;
  }
  return false;
}

/// [m] free width between the followed rows' inner canopy edges; nullopt without both rows.
std::optional<double> clear_width(const track::RowTracking& t) {
  const auto f = track::inner_faces(t);
  if (!f) return std::nullopt;
  const double w = f->left_face - f->right_face;
  return std::isfinite(w) ? std::optional<double>(w) : std::nullopt;
}

/// Both followed rows tracked from beside the robot (x_min <= 0): the robot is still between
/// rows (past a real row end they lie behind it). Sparse trees update a row every few frames
/// only, so the rows' models, not this frame's fits, decide.
bool rows_beside(const track::RowTracking& t) {
  if (t.status != track::TrackStatus::tracking) return false;
  for (const int i : {t.left, t.right}) {
    if (i < 0 || i >= static_cast<int>(t.rows.size())) return false;
    if (!(t.rows[static_cast<std::size_t>(i)].x_min <= 0.0)) return false;
  }
  return true;
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
  exit_rows_run_on_ = false;
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

bool Navigator::withdraw_end(const NavInput& in, NavOutput& out) {
  if (!config_.withdraw_end || !in.sweep_3d || !rows_beside(in.tracking)) return false;
  // Arcs along this frame's centre line (the exit's line moves with the tracked rows).
  const core::Line2& centre = *ends_.centre();
  const double moved = *ends_.end_arc() - centre.arc(declared_end_);
  if (!(moved > config_.end_withdraw_reach)) return false;
  // ...and the rows' own returns go on past the declared end, not a few returns of one ring: on
  // a 7.6 deg uphill headland, five ground returns 0.22 m above the estimated ground 4.8-5.0 m
  // ahead stretched both row models to 5 m and withdrew a right end (zoo:1:11, BENCHMARK.md).
  if (!rows_run_on_past_end(in)) return false;
  state_ = NavState::in_row;
  out.reset_end_of_row = true;
  out.events.push_back({in.stamp, NavEventKind::row_end_withdrawn, order_[leg_],
                        centre.at(*ends_.end_arc()),
                        "rows tracked on " + fmt(moved) + " m past the row end: withdrawn"});
  // This frame still along the exit's line (the ends are updated); the next one is in the row.
  out.cmd = follow_line(centre, in.T_odom_base, config_.row_speed);
  return true;
}

void Navigator::bound_exit(const NavInput& in) {
  // Once a followed row's returns were seen to run on past the declared end during this exit
  // (a row crop's blind frames ended a row that goes on), the exit follows the rows as before:
  // safe-stopped by its budget, not turned into the crop (the zoo's row crops crushed 27 -> 192
  // plants when the bound held there too). Otherwise the rows ended there, and a row end that
  // moves farther than end_withdraw_reach past it was stretched by a few stray returns (zoo:1:11:
  // an uphill headland; the exit followed them until its budget ran out): the exit ends past the
  // declared end + that reach.
  exit_rows_run_on_ = exit_rows_run_on_ || rows_run_on_past_end(in);
}

bool Navigator::rows_run_on_past_end(const NavInput& in) const {
  const auto& settle = config_.row_end_estimate;
  const double end_x = (in.T_odom_base.inverse() * declared_end_).x();
  return row_runs_on(in.tracking, in.points_base, end_x + settle.settle_tolerance,
                     settle.settle_tolerance, settle.settle_distance);
}

}  // namespace rownav::navigate
