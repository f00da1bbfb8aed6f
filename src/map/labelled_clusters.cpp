/// @file labelled_clusters.cpp Row clusters in F_l (Emmi 2021 sec. "Perception").
#include "rownav/map/labelled_clusters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "rownav/core/angle.hpp"
#include "rownav/detect/line_fit.hpp"

namespace rownav::map {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

std::int64_t cell_key(const Eigen::Vector2f& p, double cell) {
  const auto ix = static_cast<std::int64_t>(std::floor(p.x() / cell));
  const auto iy = static_cast<std::int64_t>(std::floor(p.y() / cell));
  return (ix << 32) ^ (iy & 0xffffffffLL);
}

/// Line and extent of a set of points; false when no line fits.
bool fit_row(const std::vector<Eigen::Vector2f>& pts, RowCluster& row) {
  const auto line = detect::fit_line_tls(pts);
  if (!line) return false;
  row.line = *line;
  row.arc_min = std::numeric_limits<double>::infinity();
  row.arc_max = -std::numeric_limits<double>::infinity();
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const auto& p : pts) {
    const Eigen::Vector2d q = p.cast<double>();
    const double s = row.line.arc(q);
    row.arc_min = std::min(row.arc_min, s);
    row.arc_max = std::max(row.arc_max, s);
    sum += q;
  }
  row.points = static_cast<int>(pts.size());
  row.centroid = sum / static_cast<double>(pts.size());
  return true;
}

/// Emmi 2021: "evaluating whether two clusters belong to the same row".
bool same_row(const RowCluster& a, const RowCluster& b, const LabelledClustersConfig& c) {
  const bool a_short = a.arc_max - a.arc_min < c.short_length;
  const bool b_short = b.arc_max - b.arc_min < c.short_length;
  if (a_short && b_short) return false;  // both may join a longer row instead
  if (b_short) return same_row(b, a, c);
  // From here b is long; a short a is tested against b's line only.
  if (!a_short) {
    const double cos_angle = std::abs(a.line.direction.dot(b.line.direction));
    if (cos_angle < std::cos(c.merge_angle_deg * kDegToRad)) return false;
    if (std::abs(a.line.signed_distance(b.centroid)) > c.merge_offset) return false;
  }
  if (std::abs(b.line.signed_distance(a.centroid)) > c.merge_offset) return false;
  // Gap along b's line between the two extents.
  const double a_lo = std::min(b.line.arc(a.line.at(a.arc_min)), b.line.arc(a.line.at(a.arc_max)));
  const double a_hi = std::max(b.line.arc(a.line.at(a.arc_min)), b.line.arc(a.line.at(a.arc_max)));
  const double gap = std::max(a_lo - b.arc_max, b.arc_min - a_hi);
  return gap <= c.merge_gap;
}

int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

}  // namespace

void LabelledClustersConfig::validate() const {
  core::check_positive(eps, "eps");
  core::check_positive(min_pts, "min_pts");
  core::check_positive(cell_size, "cell_size");
  core::check_non_negative(keep_behind, "keep_behind");
  core::check_positive(max_range, "max_range");
  core::check_range(keep_turn_deg, 0.0, 360.0, "keep_turn_deg");
  core::check(min_cluster_points >= 2, "min_cluster_points", "must be >= 2");
  core::check_range(merge_angle_deg, 0.0, 90.0, "merge_angle_deg");
  core::check_non_negative(merge_offset, "merge_offset");
  core::check_non_negative(merge_gap, "merge_gap");
  core::check_non_negative(short_length, "short_length");
}

LabelledClusters::LabelledClusters(const LabelledClustersConfig& config) : config_(config) {
  config_.validate();
}

int LabelledClusters::add(const std::vector<Eigen::Vector3f>& points_base,
                          const std::vector<PointLabel>& labels, const core::Pose2& T_local_base) {
  const std::size_t n = std::min(points_base.size(), labels.size());
  int stored = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (labels[i] != PointLabel::crop || !points_base[i].allFinite()) continue;
    const Eigen::Vector2d p = T_local_base * points_base[i].head<2>().cast<double>();
    if (!p.allFinite()) continue;
    const Eigen::Vector2f pf = p.cast<float>();
    cells_.try_emplace(cell_key(pf, config_.cell_size), Stored{pf, T_local_base.theta});
    ++stored;
  }
  return stored;
}

void LabelledClusters::prune(const core::Pose2& T) {
  const Eigen::Vector2d r = T.translation();
  const Eigen::Vector2d h(std::cos(T.theta), std::sin(T.theta));
  const double max_turn = config_.keep_turn_deg * std::numbers::pi / 180.0;
  for (auto it = cells_.begin(); it != cells_.end();) {
    const Eigen::Vector2d d = it->second.p.cast<double>() - r;
    const bool drop = d.dot(h) < -config_.keep_behind || d.norm() > config_.max_range ||
                      std::abs(core::angle_diff(T.theta, it->second.heading)) > max_turn;
    it = drop ? cells_.erase(it) : std::next(it);
  }
}

const std::vector<RowCluster>& LabelledClusters::update(const core::Pose2& T_local_base) {
  prune(T_local_base);
  points_.clear();
  for (const auto& [key, stored] : cells_) points_.push_back(stored.p);
  // Deterministic order (unordered_map iteration is not): sort by x then y.
  std::sort(points_.begin(), points_.end(), [](const auto& a, const auto& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y();
  });
  const auto& labels = dbscan_.run(points_, config_.eps, config_.min_pts);
  std::vector<std::vector<int>> members(static_cast<std::size_t>(dbscan_.cluster_count()));
  for (std::size_t i = 0; i < labels.size(); ++i)
    if (labels[i] >= 0) members[static_cast<std::size_t>(labels[i])].push_back(static_cast<int>(i));
  merge_rows(members);
  return rows_;
}

void LabelledClusters::merge_rows(std::vector<std::vector<int>>& members) {
  std::vector<RowCluster> parts;
  std::vector<std::vector<int>> kept;
  std::vector<Eigen::Vector2f> pts;
  for (auto& m : members) {
    if (static_cast<int>(m.size()) < config_.min_cluster_points) continue;
    pts.clear();
    for (int i : m) pts.push_back(points_[static_cast<std::size_t>(i)]);
    RowCluster row;
    if (!fit_row(pts, row)) continue;
    parts.push_back(row);
    kept.push_back(std::move(m));
  }
  std::vector<int> parent(parts.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t i = 0; i < parts.size(); ++i)
    for (std::size_t j = i + 1; j < parts.size(); ++j)
      if (same_row(parts[i], parts[j], config_))
        parent[static_cast<std::size_t>(find_root(parent, static_cast<int>(j)))] =
            find_root(parent, static_cast<int>(i));
  rows_.clear();
  for (std::size_t root = 0; root < parts.size(); ++root) {
    if (find_root(parent, static_cast<int>(root)) != static_cast<int>(root)) continue;
    pts.clear();
    int merged = 0;
    for (std::size_t j = 0; j < parts.size(); ++j) {
      if (find_root(parent, static_cast<int>(j)) != static_cast<int>(root)) continue;
      ++merged;
      for (int i : kept[j]) pts.push_back(points_[static_cast<std::size_t>(i)]);
    }
    RowCluster row;
    if (!fit_row(pts, row)) continue;
    row.merged = merged;
    rows_.push_back(row);
  }
}

void LabelledClusters::reset() {
  cells_.clear();
  rows_.clear();
}

}  // namespace rownav::map
