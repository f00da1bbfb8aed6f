// TEMPORARY minimal implementations of the end-of-row and row-end contracts
// (include/rownav/navigate/end_of_row.hpp, row_end_poles.hpp) so the closed loop runs before the
// real end_of_row.cpp / row_end_poles.cpp are merged. DELETE THIS FILE AT MERGE.
//  - end of row: fewer than point_threshold points (3D band, or 2D points) in the box ahead,
//    confirmed over confirm_frames frames (001 eq. (24)-(25), simplified);
//  - row ends: Euclidean clusters on a grid; each cluster's point nearest to the robot.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "rownav/navigate/end_of_row.hpp"
#include "rownav/navigate/row_end_poles.hpp"

namespace rownav::navigate {

void EndOfRowConfig::validate() const {
  core::check(band_z_max > band_z_min, "band_z_max", "must be > band_z_min");
  core::check(box_x_max > box_x_min, "box_x_max", "must be > box_x_min");
  core::check_non_negative(point_threshold, "point_threshold");
  core::check_positive(confirm_frames, "confirm_frames");
  core::check_non_negative(exit_distance, "exit_distance");
}

EndOfRowDetector::EndOfRowDetector(const EndOfRowConfig& config) : config_(config) {
  config_.validate();
}

void EndOfRowDetector::reset() {
  positives_ = 0;
}

EndOfRowResult EndOfRowDetector::update(const core::PointCloud& cloud_base,
                                        std::span<const Eigen::Vector2f> points_base,
                                        const track::RowTracking& tracking) {
  const double half = tracking.row_spacing > 0.0 ? tracking.row_spacing : 2.0;
  int n = 0;
  auto in_box = [&](double x, double y) {
    return x >= config_.box_x_min && x <= config_.box_x_max && std::abs(y) <= half;
  };
  if (!cloud_base.empty()) {
    for (const auto& p : cloud_base.points)
      if (p.finite() && p.z >= config_.band_z_min && p.z <= config_.band_z_max && in_box(p.x, p.y))
        ++n;
  } else {
    for (const auto& p : points_base)
      if (p.allFinite() && in_box(p.x(), p.y())) ++n;
  }
  EndOfRowResult r;
  r.box_points = n;
  positives_ = n < config_.point_threshold ? positives_ + 1 : 0;
  r.end_detected = positives_ >= config_.confirm_frames;
  r.confidence = r.end_detected ? 1.0 : static_cast<double>(positives_) / config_.confirm_frames;
  return r;
}

void RowEndConfig::validate() const {
  core::check_positive(cluster_tolerance, "cluster_tolerance");
  core::check_positive(min_cluster_points, "min_cluster_points");
  core::check_positive(ransac_iterations, "ransac_iterations");
  core::check_positive(ransac_threshold, "ransac_threshold");
}

namespace {
int find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}
}  // namespace

RowEnds estimate_row_ends(std::span<const Eigen::Vector2f> points_base, double /*row_heading*/,
                          double /*spacing*/, const RowEndConfig& config) {
  RowEnds out;
  const double cell = config.cluster_tolerance;
  std::vector<Eigen::Vector2f> pts;
  for (const auto& p : points_base)
    if (p.allFinite()) pts.push_back(p);
  const int n = static_cast<int>(pts.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::unordered_map<long long, std::vector<int>> grid;
  auto key = [](long long cx, long long cy) { return cx * 1000003LL + cy; };
  for (int i = 0; i < n; ++i)
    grid[key(std::llround(std::floor(pts[i].x() / cell)),
             std::llround(std::floor(pts[i].y() / cell)))]
        .push_back(i);
  for (int i = 0; i < n; ++i) {
    const long long cx = std::llround(std::floor(pts[i].x() / cell));
    const long long cy = std::llround(std::floor(pts[i].y() / cell));
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy) {
        auto it = grid.find(key(cx + dx, cy + dy));
        if (it == grid.end()) continue;
        for (int j : it->second)
          if (j > i && (pts[i] - pts[j]).norm() <= cell) parent[find(parent, i)] = find(parent, j);
      }
  }
  std::unordered_map<int, std::pair<int, int>> clusters;  // root -> (count, nearest index)
  for (int i = 0; i < n; ++i) {
    auto& c = clusters.try_emplace(find(parent, i), 0, i).first->second;
    ++c.first;
    if (pts[i].squaredNorm() < pts[c.second].squaredNorm()) c.second = i;
  }
  for (const auto& [root, c] : clusters)
    if (c.first >= config.min_cluster_points) out.poles.push_back(pts[c.second].cast<double>());
  std::sort(out.poles.begin(), out.poles.end(),
            [](const auto& a, const auto& b) { return a.norm() < b.norm(); });
  for (const auto& p : out.poles) {
    if (p.y() > 0.0 && !out.left_end) out.left_end = p;
    if (p.y() < 0.0 && !out.right_end) out.right_end = p;
  }
  return out;
}

}  // namespace rownav::navigate
