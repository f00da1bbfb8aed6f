#include "rownav/navigate/end_of_row.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <vector>

namespace rownav::navigate {

namespace {

struct BoxCount {
  int left = 0, right = 0;
  double x_last = -1.0;  // [m] farthest counted point with x <= box_x_max (-1: none)
  int near = 0;          // planar: returns beside the robot, x in [0, box_x_min)
  bool in_view = true;   // 3D: some ray ahead comes down to the band's floor in the box
};

// Half width of the box: the two followed rows when the spacing is known (003 sec. II-C), the
// paper's 3 m wide range otherwise (001 eq. 24).
double half_width(const EndOfRowConfig& c, const track::RowTracking& t) {
  if (std::isfinite(t.row_spacing) && t.row_spacing > 0.0)
    return 0.5 * t.row_spacing + c.row_margin;
  return c.default_half_width;
}

// 3D (check_view): the squared slope a ray needs to come down from the sensor to band_z_min by
// box_x_max; 0 when the check does not apply (a sensor below the band, or beyond the box).
double needed_descent2(const EndOfRowConfig& c, const Eigen::Vector3f& sensor) {
  const double run = c.box_x_max - double(sensor.x()), drop = double(sensor.z()) - c.band_z_min;
  if (!c.check_view || drop <= 0.0 || run <= 0.0) return 0.0;
  return (drop / run) * (drop / run);
}

// 3D cloud: points of the height band (001 sec. 4: 0.5-1.3 m) in x in [box_x_min, box_x_max],
// per side. x_last is taken over [0, box_x_max]: the last plant seen before the box.
// in_view: any return gives the slope of the ray it ended (from the sensor's origin), whatever it
// hit; the box's band is in view when one ray ahead inside the box's half width is that steep.
BoxCount count_cloud(const core::PointCloud& cloud, const EndOfRowConfig& c, double hw,
                     const Eigen::Vector3f& sensor) {
  BoxCount n;
  const double need2 = needed_descent2(c, sensor);
  n.in_view = need2 <= 0.0;
  for (const auto& p : cloud.points) {
    if (!p.finite() || std::abs(p.y) > hw) continue;
    if (!n.in_view && p.x > sensor.x() && p.z < sensor.z()) {
      const float dz = sensor.z() - p.z, dx = p.x - sensor.x(), dy = p.y - sensor.y();
      n.in_view = double(dz * dz) >= need2 * double(dx * dx + dy * dy);
    }
    if (p.z < c.band_z_min || p.z > c.band_z_max) continue;
    if (p.x >= 0.0 && p.x <= c.box_x_max) n.x_last = std::max(n.x_last, double(p.x));
    if (p.x < c.box_x_min || p.x > c.box_x_max) continue;
    (p.y > 0.0f ? n.left : n.right) += 1;
  }
  return n;
}

// Planar scan: every point in the rectangle (003 sec. II-C), counted as "left" for the total;
// `near`: the returns beside the robot, before the box (the blindness test).
BoxCount count_scan(std::span<const Eigen::Vector2f> pts, const EndOfRowConfig& c, double hw) {
  BoxCount n;
  for (const auto& p : pts) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || std::abs(p.y()) > hw) continue;
    if (p.x() >= 0.0f && p.x() <= c.box_x_max) n.x_last = std::max(n.x_last, double(p.x()));
    if (p.x() >= 0.0f && p.x() < c.box_x_min) ++n.near;
    if (p.x() >= c.box_x_min && p.x() <= c.box_x_max) ++n.left;
  }
  return n;
}

// The lane at the box's near edge: between the followed rows' inner faces (a row's own
// returns before the box are the row, not an occluder), else the box's half width.
struct Lane {
  double right, left;  // [m] y bounds at x = box_x_min (base frame)
};
Lane lane_at_box(const track::RowTracking& t, const EndOfRowConfig& c, double hw) {
  const auto f = track::inner_faces(t);
  if (!f) return {-hw, hw};
  // The inner faces at the box's near edge (rows oriented forward, headings in the base frame).
  const Lane lane{f->right_face + c.box_x_min * std::tan(f->right->heading),
                  f->left_face + c.box_x_min * std::tan(f->left->heading)};
  if (!std::isfinite(lane.right) || !std::isfinite(lane.left) || lane.left <= lane.right)
    return {-hw, hw};
  return lane;
}

// One planar return seen from the scanner: bearing, range, and whether it lies in the lane
// before the box.
struct Return {
  double bearing, range;
  bool near;
  Eigen::Vector2f p;
};

// Angular bins over the lane's view of the box, each holding its nearest return.
class ShadowBins {
 public:
  ShadowBins(double lo, double hi, double bin)
      : lo_(lo),
        bin_(bin),
        n_(std::max(1, static_cast<int>(std::ceil((hi - lo) / bin)))),
        hi_(hi),
        nearest_(static_cast<std::size_t>(n_), 1e300),
        near_(static_cast<std::size_t>(n_), 0) {}
  /// Bearings [a0, a1] hidden at range r by a return (near: in the lane before the box).
  void mark(double a0, double a1, double r, bool near) {
    if (a1 <= lo_ || a0 >= hi_) return;
    const int k0 = std::clamp(int(std::floor((a0 - lo_) / bin_)), 0, n_ - 1);
    const int k1 = std::clamp(int(std::floor((a1 - lo_) / bin_)), 0, n_ - 1);
    for (auto k = static_cast<std::size_t>(k0); k <= static_cast<std::size_t>(k1); ++k)
      if (r < nearest_[k]) nearest_[k] = r, near_[k] = near;
  }
  double share() const {
    int shadowed = 0;
    for (const char h : near_) shadowed += h ? 1 : 0;
    return double(shadowed) / n_;
  }

 private:
  double lo_, bin_;
  int n_;
  double hi_;
  std::vector<double> nearest_;
  std::vector<char> near_;
};

// The planar returns ahead of the scanner, sorted by bearing.
std::vector<Return> returns_by_bearing(std::span<const Eigen::Vector2f> pts,
                                       const EndOfRowConfig& c, const Lane& lane,
                                       const Eigen::Vector2f& sensor) {
  std::vector<Return> rs;
  for (const auto& p : pts) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || p.x() <= sensor.x()) continue;
    const Eigen::Vector2f q = p - sensor;
    const bool near = p.x() < c.box_x_min && p.y() >= lane.right && p.y() <= lane.left;
    rs.push_back({std::atan2(double(q.y()), double(q.x())), double(q.norm()), near, p});
  }
  std::sort(rs.begin(), rs.end(),
            [](const Return& a, const Return& b) { return a.bearing < b.bearing; });
  return rs;
}

// Chains of near returns next to each other in bearing and closer than shadow_link (voxel
// centroids of one surface) that cross shadow_wall of the lane's width: a wall, closed between
// its returns. A clump of weeds narrower than that keeps the gaps between its returns.
void close_walls(std::vector<Return> near, const EndOfRowConfig& c, const Lane& lane,
                 ShadowBins& bins) {
  std::erase_if(near, [](const Return& r) { return !r.near; });
  const double wall = c.shadow_wall * (lane.left - lane.right);
  for (std::size_t i = 0; i < near.size();) {
    std::size_t j = i;
    float y_min = near[i].p.y(), y_max = near[i].p.y();
    while (j + 1 < near.size() && (near[j].p - near[j + 1].p).norm() <= c.shadow_link) {
      ++j;
      y_min = std::min(y_min, near[j].p.y());
      y_max = std::max(y_max, near[j].p.y());
    }
    if (j > i && double(y_max - y_min) >= wall)
      for (std::size_t k = i; k < j; ++k)
        bins.mark(near[k].bearing, near[k + 1].bearing, std::min(near[k].range, near[k + 1].range),
                  true);
    i = j + 1;
  }
}

// Planar scan: share of the lane's view of the box that nearer returns in the lane shadow. The
// beams of one plane stop at the first thing they meet: a weed or a leaf in the lane ahead, or
// the ground where the scan plane pitches into a bump, hides the box as completely as the
// headland's open ground empties it, and only the second is a row end (issue 11: "many" weeds
// in a 0.8 m vegetable bed ended the row 3.5 m early; rough zoo vineyards ended it at the first
// bump). Bins of shadow_bin_deg over the lane's angular span at the box seen from the scanner
// (a weed touching it hides the whole box); a bin is shadowed when its nearest return lies
// before the box (x < box_x_min) inside the lane, or between two returns of a wall.
double shadowed_share(std::span<const Eigen::Vector2f> pts, const EndOfRowConfig& c,
                      const Lane& lane, const Eigen::Vector2f& sensor) {
  const double dx = c.box_x_min - double(sensor.x());
  if (!(dx > 0.0)) return 0.0;  // the scanner at or beyond the box: nothing can hide it
  ShadowBins bins(std::atan2(lane.right - double(sensor.y()), dx),
                  std::atan2(lane.left - double(sensor.y()), dx),
                  c.shadow_bin_deg * std::numbers::pi / 180.0);
  const std::vector<Return> rs = returns_by_bearing(pts, c, lane, sensor);
  for (const Return& r : rs) bins.mark(r.bearing, r.bearing, r.range, r.near);
  close_walls(rs, c, lane, bins);
  return bins.share();
}

// The followed rows' extent: the nearest and the farthest x_max of the followed rows, when
// tracked.
struct Extent {
  double nearest, farthest;
};
std::optional<Extent> followed_extent(const track::RowTracking& t) {
  if (t.status != track::TrackStatus::tracking) return std::nullopt;
  std::optional<Extent> out;
  for (const int i : {t.left, t.right}) {
    if (i < 0 || i >= static_cast<int>(t.rows.size())) continue;
    const double x = t.rows[static_cast<std::size_t>(i)].x_max;
    if (!std::isfinite(x)) continue;
    out = out ? Extent{std::min(out->nearest, x), std::max(out->farthest, x)} : Extent{x, x};
  }
  return out;
}

}  // namespace

void EndOfRowConfig::validate() const {
  core::check(band_z_min < band_z_max, "band_z_min", "must be < band_z_max");
  core::check_non_negative(box_x_min, "box_x_min");
  core::check(box_x_min < box_x_max, "box_x_min", "must be < box_x_max");
  core::check_positive(point_threshold, "point_threshold");
  core::check_positive(confirm_frames, "confirm_frames");
  core::check_non_negative(exit_distance, "exit_distance");
  core::check_positive(default_half_width, "default_half_width");
  core::check_non_negative(row_margin, "row_margin");
  core::check_non_negative(count_jump, "count_jump");
  core::check_positive(scan_point_threshold, "scan_point_threshold");
  core::check_range(max_shadowed, 0.0, 1.0, "max_shadowed");
  core::check_range(shadow_bin_deg, 0.05, 45.0, "shadow_bin_deg");
  core::check_non_negative(shadow_link, "shadow_link");
  core::check_range(shadow_wall, 0.0, 1.0, "shadow_wall");
  core::check_positive(extent_distance, "extent_distance");
  core::check_range(blind_near_ratio, 0.0, 1.0, "blind_near_ratio");
  core::check_positive(blind_history, "blind_history");
}

EndOfRowDetector::EndOfRowDetector(const EndOfRowConfig& config)
    : config_((config.validate(), config)) {}

void EndOfRowDetector::reset() {
  positives_ = 0;
  previous_count_ = -1;
  declared_ = false;
  near_counts_.clear();
}

bool EndOfRowDetector::blind(int near) {
  bool blind = false;
  if (!near_counts_.empty()) {
    std::vector<int> v(near_counts_.begin(), near_counts_.end());
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    blind = near < config_.blind_near_ratio * v[v.size() / 2];
  }
  if (blind) return true;  // a blind frame does not lower the reference
  near_counts_.push_back(near);
  while (static_cast<int>(near_counts_.size()) > config_.blind_history) near_counts_.pop_front();
  return false;
}

EndOfRowResult EndOfRowDetector::update(const core::PointCloud& cloud_base,
                                        std::span<const Eigen::Vector2f> points_base,
                                        const track::RowTracking& tracking,
                                        const Eigen::Vector3f& sensor_base) {
  const EndOfRowConfig& c = config_;
  const double hw = half_width(c, tracking);
  const bool planar = cloud_base.empty();
  const BoxCount n =
      planar ? count_scan(points_base, c, hw) : count_cloud(cloud_base, c, hw, sensor_base);
  EndOfRowResult r;
  // No evidence either way (the count keeps its state).
  if (planar ? blind(n.near) : !n.in_view) {
    r.blind = true;
    r.box_seen = false;
    r.end_detected = declared_;
    r.confidence = declared_ ? 1.0 : std::min(1.0, double(positives_) / c.confirm_frames);
    return r;
  }
  r.box_points = n.left + n.right;
  r.left_points = planar ? 0 : n.left;
  r.right_points = planar ? 0 : n.right;
  // 001 eq. (24): an abrupt change of the count announces the end.
  r.count_jump = previous_count_ >= 0 && std::abs(r.box_points - previous_count_) > c.count_jump;
  previous_count_ = r.box_points;
  // 001 eq. (25) / sec. 4 (n < 30 on the left and right sides); 003 sec. II-C for planar scans.
  // A sparse canopy (young shoots, 16 beams) can leave the box under the threshold mid-row: the
  // count is overruled while a followed row is tracked beyond the box (plants ahead): the rows
  // end where they all end, a gap of missing trees in one row is no row end (issue 10).
  const std::optional<Extent> extent = followed_extent(tracking);
  const bool rows_continue = extent && extent->farthest > c.box_x_max;
  // A planar scan's view of the box hidden by something nearer: neither cue is evidence (the
  // rows' tracked extent ends where the occluder hides them, too).
  const bool seen = !planar || shadowed_share(points_base, c, lane_at_box(tracking, c, hw),
                                              sensor_base.head<2>()) <= c.max_shadowed;
  const bool count_end = !rows_continue && seen &&
                         (planar ? r.box_points < c.scan_point_threshold
                                 : n.left < c.point_threshold && n.right < c.point_threshold);
  // Extent cue: every followed row ends (a gap in one row ends that row's support only).
  const bool extent_end = c.use_extent && seen && extent && extent->farthest < c.extent_distance;
  r.frame_positive = count_end || extent_end;
  r.box_seen = seen;
  positives_ = r.frame_positive ? positives_ + 1 : 0;
  declared_ = declared_ || positives_ >= c.confirm_frames;
  r.end_detected = declared_;
  // Distance to the last plants: the tracked extent, else the last band point before the box.
  if (extent)
    r.distance_to_end = extent->farthest;
  else if (count_end && n.x_last >= 0.0)
    r.distance_to_end = n.x_last;
  // Share of the confirmation window seen positive; 1 once declared.
  r.confidence = declared_ ? 1.0 : std::min(1.0, double(positives_) / c.confirm_frames);
  return r;
}

}  // namespace rownav::navigate
