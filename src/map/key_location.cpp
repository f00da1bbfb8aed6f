/// @file key_location.cpp Key locations from the row clusters (Emmi 2021 eq. (2)-(3), Fig. 3).
#include "rownav/map/key_location.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rownav::map {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

Eigen::Vector2d heading_of(const core::Pose2& T) { return {std::cos(T.theta), std::sin(T.theta)}; }

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Row direction turned along the robot heading.
Eigen::Vector2d along(const RowCluster& row, const Eigen::Vector2d& h) {
  return row.line.direction.dot(h) >= 0.0 ? row.line.direction : Eigen::Vector2d(-row.line.direction);
}

/// Emmi 2021 Fig. 3: the furthest (exit) or nearest (entry) plant of a row ahead of the robot,
/// projected by d towards the robot's side; nullopt when that plant is not ahead.
std::optional<KeyLocation> project(const RowCluster& row, KeyType type, double side_sign,
                                   double d, const core::Pose2& T) {
  const Eigen::Vector2d h = heading_of(T);
  const Eigen::Vector2d u = along(row, h);
  const bool forward = u.dot(row.line.direction) > 0.0;
  const bool far_end = type == KeyType::exit;
  const double s = (forward == far_end) ? row.arc_max : row.arc_min;
  const Eigen::Vector2d q = row.line.at(s);
  if ((q - T.translation()).dot(h) <= 0.0) return std::nullopt;
  KeyLocation k;
  k.type = type;
  k.side = side_sign > 0.0 ? KeySide::left : KeySide::right;
  k.p = q - side_sign * d * Eigen::Vector2d(-u.y(), u.x());
  k.v = u;
  k.half_width = d;
  return k;
}

/// Left and right fused into middle, eq. (2)-(3); too far apart, one side is dropped instead.
std::vector<KeyLocation> fuse(const std::optional<KeyLocation>& l,
                              const std::optional<KeyLocation>& r, const core::Pose2& T,
                              double max_separation) {
  if (l && r) {
    if ((l->p - r->p).norm() <= max_separation) {
      KeyLocation m = *l;
      m.side = KeySide::middle;
      m.p = 0.5 * (l->p + r->p);             // Emmi 2021 eq. (2)
      m.v = (0.5 * (l->v + r->v)).normalized();  // Emmi 2021 eq. (3), k = 1/2, kept unit
      m.half_width = 0.5 * (l->half_width + r->half_width);
      return {m};
    }
    // Emmi 2021: drop the furthest entry / the closest exit.
    const double dl = (l->p - T.translation()).norm(), dr = (r->p - T.translation()).norm();
    const bool keep_left = (l->type == KeyType::entry) == (dl < dr);
    return {keep_left ? *l : *r};
  }
  if (l) return {*l};
  if (r) return {*r};
  return {};
}

}  // namespace

void KeyLocationConfig::validate() const {
  core::check_positive(lane_width, "lane_width");
  core::check_positive(min_width_ratio, "min_width_ratio");
  core::check(max_width_ratio >= min_width_ratio, "max_width_ratio", "must be >= min_width_ratio");
  core::check_positive(max_lateral_ratio, "max_lateral_ratio");
  core::check_range(side_max_angle_deg, 0.0, 90.0, "side_max_angle_deg");
  core::check_positive(max_distance, "max_distance");
  core::check_range(max_orientation_deg, 0.0, 90.0, "max_orientation_deg");
  core::check_non_negative(max_alignment, "max_alignment");
  core::check_non_negative(same_radius, "same_radius");
  core::check_non_negative(max_side_separation, "max_side_separation");
}

std::optional<double> side_lateral(const RowCluster& row, const core::Pose2& T,
                                   double half_width, const KeyLocationConfig& c) {
  const Eigen::Vector2d u = along(row, heading_of(T));
  if (u.dot(heading_of(T)) < std::cos(c.side_max_angle_deg * kDegToRad)) return std::nullopt;
  const double lateral = cross(u, row.line.point - T.translation());
  if (std::abs(lateral) > c.max_lateral_ratio * 2.0 * half_width || lateral == 0.0)
    return std::nullopt;
  return lateral;
}

SideRows find_side_rows(const std::vector<RowCluster>& rows, const core::Pose2& T,
                        double half_width, const KeyLocationConfig& c) {
  SideRows out;
  for (const auto& row : rows) {
    const auto lat = side_lateral(row, T, half_width, c);
    if (!lat) continue;
    if (*lat > 0.0 && (!out.left || *lat < out.left_lateral)) {
      out.left = &row;
      out.left_lateral = *lat;
    } else if (*lat < 0.0 && (!out.right || -*lat < out.right_lateral)) {
      out.right = &row;
      out.right_lateral = -*lat;
    }
  }
  return out;
}

KeyLocator::KeyLocator(const KeyLocationConfig& config) : config_(config) {
  config_.validate();
  d_ = 0.5 * config_.lane_width;
}

void KeyLocator::reset() {
  d_ = 0.5 * config_.lane_width;
  last_ = {};
}

bool KeyLocator::set_lane_width(double lane_width) {
  if (!std::isfinite(lane_width) || lane_width <= 0.0) return false;
  const double d0 = 0.5 * lane_width;
  // d keeps what the centroids measured, within the bounds of the new a priori width.
  d_ = std::clamp(d_ * lane_width / config_.lane_width, config_.min_width_ratio * d0,
                  config_.max_width_ratio * d0);
  config_.lane_width = lane_width;
  return true;
}

void KeyLocator::update_width(const SideRows& sides, const core::Pose2& T) {
  if (!sides.left || !sides.right) return;
  // Emmi 2021: d from the centroids of the left and right rows nearest the robot (measured
  // across the rows, so that clusters of different extents do not bias it).
  const Eigen::Vector2d u = along(*sides.left, heading_of(T));
  const double across = std::abs(cross(u, sides.left->centroid - sides.right->centroid));
  const double d0 = 0.5 * config_.lane_width;
  d_ = std::clamp(0.5 * across, config_.min_width_ratio * d0, config_.max_width_ratio * d0);
}

KeyVerdict KeyLocator::check(const KeyLocation& k, const core::Pose2& T) const {
  const Eigen::Vector2d h = heading_of(T);
  const Eigen::Vector2d d = k.p - T.translation();
  const double min_cos = std::cos(config_.max_orientation_deg * kDegToRad);
  if (d.dot(h) < 0.0) return KeyVerdict::behind;           // rule (i)
  if (d.norm() > config_.max_distance) return KeyVerdict::too_far;  // rule (ii)
  if (k.type == KeyType::exit || config_.gate_entry_by_robot) {  // rule (iv)
    if (k.v.dot(h) < min_cos) return KeyVerdict::misoriented;
    if (std::abs(cross(h, d)) > config_.max_alignment) return KeyVerdict::misaligned;
  }
  const auto& prev = last(k.type);  // rule (iii)
  if (prev && k.type == KeyType::entry && k.v.dot(prev->v) >= min_cos &&
      std::abs(cross(prev->v, k.p - prev->p)) <= config_.max_alignment &&
      (k.p - prev->p).dot(prev->v) > config_.same_radius)
    return KeyVerdict::beyond_entry;  // rownav: the same lane's entry does not move forward
  if (prev && (k.p - prev->p).norm() <= config_.same_radius) {
    if (k.v.dot(prev->v) < min_cos) return KeyVerdict::misoriented;
    if (std::abs(cross(prev->v, k.p - prev->p)) > config_.max_alignment) return KeyVerdict::jump;
  }
  return KeyVerdict::valid;
}

std::vector<KeyLocation> KeyLocator::update(const std::vector<RowCluster>& rows,
                                            const core::Pose2& T) {
  const SideRows sides = find_side_rows(rows, T, d_, config_);
  update_width(sides, T);
  std::vector<KeyLocation> valid;
  for (const KeyType type : {KeyType::entry, KeyType::exit}) {
    std::optional<KeyLocation> l, r;
    if (sides.left) l = project(*sides.left, type, 1.0, d_, T);
    if (sides.right) r = project(*sides.right, type, -1.0, d_, T);
    for (const auto& k : fuse(l, r, T, config_.max_side_separation)) {
      if (check(k, T) != KeyVerdict::valid) continue;
      last_[static_cast<std::size_t>(type)] = k;
      valid.push_back(k);
      break;
    }
  }
  return valid;
}

}  // namespace rownav::map
