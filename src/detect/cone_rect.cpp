// Bertoglio 2023 (003_25dc0df51a1e5faf.txt) sec. II-B, after Kamaro's FRE 2021 row crawler:
// find_cone grows the two sides of a cone centred on the robot heading until N points fall
// inside; the cone centre line gives the heading; two rectangles grown sideways until N points
// fall inside give the distances to the rows. Growing until the N-th point is reached equals
// taking the N-th smallest angle (distance), so no step size is needed.
#include "rownav/detect/cone_rect.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>

namespace rownav::detect {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// N-th smallest value of buf (1-based), nullopt when fewer than n values.
std::optional<double> nth_smallest(std::vector<float>& buf, int n) {
  if (n < 1 || static_cast<int>(buf.size()) < n) return std::nullopt;
  const auto it = buf.begin() + (n - 1);
  std::nth_element(buf.begin(), it, buf.end());
  return *it;
}

struct Sides {
  std::optional<double> left, right;  // [rad] cone side angles or [m] rectangle distances
};

// Bertoglio 2023: each cone side moves outwards from the heading until N points are inside
// its half of the cone (radius side_length).
Sides grow_cone(const std::vector<Eigen::Vector2f>& pts, const ConeRectConfig& c,
                std::vector<float>& buf) {
  Sides s;
  const double max_a = c.max_cone_half_angle_deg * kDeg, l2 = c.side_length * c.side_length;
  for (const int sign : {1, -1}) {
    buf.clear();
    for (const auto& p : pts) {
      if (!p.allFinite() || p.x() <= 0.0f || p.squaredNorm() > l2) continue;
      const double a = sign * std::atan2(p.y(), p.x());
      if (a >= 0.0 && a <= max_a) buf.push_back(static_cast<float>(a));
    }
    const auto a = nth_smallest(buf, c.cone_points);
    (sign > 0 ? s.left : s.right) = a ? std::optional<double>(sign * *a) : std::nullopt;
  }
  return s;
}

// Bertoglio 2023: rectangles beside the robot grow outwards until N points are inside; in the
// frame rotated by `heading` (0 = the robot's axes, as in the paper). A window with no return
// at all (a robot before the rows) starts at its side's first return ahead, when that is within
// rect_slide_ahead (rownav, issue 11); on a planar scan only when both windows are empty
// (`per_side` false). Starting at the rows' first return, not at the first shift that holds any,
// keeps a near row's start from giving fewer than N returns and the row behind it the N-th.
Sides grow_rectangles(const std::vector<Eigen::Vector2f>& pts, const ConeRectConfig& c,
                      double heading, bool per_side, std::vector<float>& buf) {
  const float ch = static_cast<float>(std::cos(heading)),
              sh = static_cast<float>(std::sin(heading));
  const auto x_lo = static_cast<float>(c.rect_x_min), x_hi = static_cast<float>(c.rect_x_max);
  // Per side (0: left, 1: right): the window's start and whether it holds a return.
  float lo[2] = {x_lo, x_lo},
        first[2] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
  bool beside[2] = {false, false};
  for (const auto& p : pts) {
    if (!p.allFinite()) continue;
    const float x = ch * p.x() + sh * p.y(), y = -sh * p.x() + ch * p.y();
    if (y == 0.0f || std::abs(y) > c.max_rect_width) continue;
    const int k = y > 0.0f ? 0 : 1;
    beside[k] = beside[k] || (x >= x_lo && x <= x_hi);
    if (x > x_hi) first[k] = std::min(first[k], x);
  }
  const bool none_beside = !beside[0] && !beside[1];
  for (int k = 0; k < 2; ++k)
    if (!beside[k] && (per_side || none_beside) && first[k] - x_lo <= c.rect_slide_ahead)
      lo[k] = first[k];
  Sides s;
  for (const int sign : {1, -1}) {
    const float a = lo[sign > 0 ? 0 : 1], b = a + (x_hi - x_lo);
    buf.clear();
    for (const auto& p : pts) {
      if (!p.allFinite()) continue;
      const float x = ch * p.x() + sh * p.y(), y = sign * (-sh * p.x() + ch * p.y());
      if (x >= a && x <= b && y > 0.0f && y <= c.max_rect_width) buf.push_back(y);
    }
    (sign > 0 ? s.left : s.right) = nth_smallest(buf, c.rect_points);
  }
  return s;
}

// Cone centre minus the part due to an off-centre robot (see ConeRectConfig::compensate_offset).
double corrected_heading(double centre, const Sides& d, const ConeRectConfig& c) {
  if (!c.compensate_offset || !d.left || !d.right) return centre;
  auto a = [&](double dist) { return std::asin(std::min(1.0, dist / c.side_length)); };
  return centre - 0.5 * (a(*d.left) - a(*d.right));
}

core::RowLine side_line(double heading, double signed_dist, const ConeRectConfig& c) {
  const Eigen::Vector2d dir(std::cos(heading), std::sin(heading));
  core::RowLine r;
  r.line = core::Line2(signed_dist * Eigen::Vector2d(-dir.y(), dir.x()), dir);
  r.heading = heading;
  r.offset = r.line.y_at(0.0);
  r.x_min = c.rect_x_min;
  r.x_max = c.rect_x_max;
  r.support = c.rect_points;
  return r;
}

// The row behind a side's inner edge: the returns from the edge to `depth` behind it set the
// reported row's extent along x and its support. The edge is the rectangle's N-th nearest return,
// so the band starts half a depth in front of it (the N - 1 nearer ones).
void row_extent(std::span<const Eigen::Vector2f> pts, double depth, core::RowLine& r) {
  const Eigen::Vector2d n(-r.line.direction.y(), r.line.direction.x());
  const double edge = n.dot(r.line.point), out = edge >= 0.0 ? 1.0 : -1.0;
  int count = 0;
  double x_min = 0.0, x_max = 0.0;
  for (const auto& p : pts) {
    if (!p.allFinite()) continue;
    const double behind = out * (n.dot(p.cast<double>()) - edge);
    if (behind < -0.5 * depth || behind > depth) continue;
    x_min = count ? std::min(x_min, double(p.x())) : double(p.x());
    x_max = count ? std::max(x_max, double(p.x())) : double(p.x());
    ++count;
  }
  if (count == 0) return;  // not reached: the edge is a return
  r.x_min = x_min, r.x_max = x_max, r.support = count;
}

// Issue 11: the rectangles see only x in [rect_x_min, rect_x_max]; where the near row has fewer
// than N returns there (a 2D scan through a sparse canopy) they grow on to the row behind. A row
// band between the robot and a hit, over the whole visible row, sets that side at the band's
// inner edge (its N-th nearest return, as the rectangle would have stopped; nearest_row.hpp).
void step_in(const std::vector<Eigen::Vector2f>& pts, const ConeRectConfig& c, double heading,
             Sides& d) {
  if (!d.left || !d.right) return;
  core::RowObservation sides;
  sides.rows = {side_line(heading, -*d.right, c), side_line(heading, *d.left, c)};
  sides.right = 0, sides.left = 1;
  const auto bands = find_nearer_rows(sides, pts, heading, c.nearest_row, c.rect_points);
  if (bands[0]) d.left = bands[0]->inner;
  if (bands[1]) d.right = -bands[1]->inner;
}

}  // namespace

void ConeRectConfig::validate() const {
  core::check_positive(side_length, "side_length");
  core::check(cone_points >= 1, "cone_points", "must be >= 1");
  core::check(max_cone_half_angle_deg > 0.0 && max_cone_half_angle_deg < 90.0,
              "max_cone_half_angle_deg", "must be in (0, 90)");
  core::check(rect_x_min < rect_x_max, "rect_x_max", "must be > rect_x_min");
  core::check(rect_points >= 1, "rect_points", "must be >= 1");
  core::check_non_negative(rect_slide_ahead, "rect_slide_ahead");
  core::check_positive(max_rect_width, "max_rect_width");
  core::check_non_negative(min_width, "min_width");
  core::check_positive(row_depth, "row_depth");
  core::validate_nested(row_direction, "row_direction");
  core::validate_nested(nearest_row, "nearest_row");
}

ConeRectDetector::ConeRectDetector(const ConeRectConfig& config) : config_(config) {
  config_.validate();
}

core::RowObservation ConeRectDetector::detect(const DetectorInput& input) {
  const auto& c = config_;
  core::RowObservation obs;
  obs.stamp = input.stamp;
  const Sides cone = grow_cone(input.points, c, buf_);
  // A planar scanner's gap beside the robot, its near row ahead hidden, would slide a window to
  // the row behind it (tests/detect/nearest_row_2d_test.cpp: gross 0.47 -> 0.62 %).
  const bool per_side = !input.planar_scan;
  const bool has_cone = cone.left && cone.right;
  double heading = has_cone ? 0.5 * (*cone.left + *cone.right) : 0.0;
  const auto sharp =
      input.planar_scan ? row_direction(input.points, c.row_direction) : std::nullopt;
  if (sharp) heading = *sharp;
  Sides d = grow_rectangles(input.points, c, c.align_rectangles ? heading : 0.0, per_side, buf_);
  if (!sharp && has_cone && c.compensate_offset && d.left && d.right) {  // corrected heading
    heading = corrected_heading(0.5 * (*cone.left + *cone.right), d, c);
    if (c.align_rectangles) d = grow_rectangles(input.points, c, heading, per_side, buf_);
  }
  if (c.nearest_row.enabled && (input.planar_scan || c.nearest_row.on_clouds))
    step_in(input.points, c, heading, d);
  if (d.left && d.right && *d.left + *d.right < c.min_width) d = {};  // clutter, not a corridor
  if (d.right) obs.rows.push_back(side_line(heading, -*d.right, c));
  if (d.left) obs.rows.push_back(side_line(heading, *d.left, c));
  const double depth =
      d.left && d.right ? std::min(c.row_depth, 0.5 * (*d.left + *d.right)) : c.row_depth;
  for (auto& r : obs.rows) row_extent(input.points, depth, r);
  if (d.right) obs.right = 0;
  if (d.left) obs.left = d.right ? 1 : 0;
  obs.heading = heading;
  obs.confidence = (d.left ? 0.5 : 0.0) + (d.right ? 0.5 : 0.0);
  if (!has_cone && !sharp) obs.confidence *= 0.5;
  if (d.left && d.right) {
    const double half = 0.5 * (*d.left - *d.right);
    core::CorridorObservation corr;
    corr.heading = heading;
    corr.offset = half / std::cos(heading);  // y at x = 0 of the centre line
    corr.width = *d.left + *d.right;
    obs.corridor = corr;
  }
  obs.status = obs.rows.empty()                        ? core::DetectionStatus::no_rows
               : (obs.corridor && (has_cone || sharp)) ? core::DetectionStatus::ok
                                                       : core::DetectionStatus::degraded;
  return obs;
}

}  // namespace rownav::detect
