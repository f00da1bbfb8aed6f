#include "rownav/sim/field_truth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "rownav/core/angle.hpp"

namespace rownav::sim {
namespace {

constexpr double kCorridorStep = 0.25;  // [m] corridor centre sampling along the row

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Point at arc length s of a polyline, extending the first / last segment beyond the ends.
Eigen::Vector2d point_at_arc(const std::vector<Eigen::Vector2d>& line, double s) {
  for (std::size_t i = 1; i < line.size(); ++i) {
    const Eigen::Vector2d d = line[i] - line[i - 1];
    const double l = d.norm();
    if (l <= 0.0) continue;
    if (s <= l || i + 1 == line.size()) return line[i - 1] + (s / l) * d;
    s -= l;
  }
  return line.front();
}

/// Centre of corridor between rows a and b: midpoints of a's samples and their feet on b,
/// over the union of both rows' extents along a.
std::vector<Eigen::Vector2d> corridor_midline(const Row& a, const Row& b) {
  const double la = a.length();
  const double s0 = std::min(0.0, project_on_polyline(a.polyline, b.start()).along);
  const double s1 = std::max(la, project_on_polyline(a.polyline, b.end()).along);
  const int n = std::max(1, static_cast<int>(std::ceil((s1 - s0) / kCorridorStep)));
  std::vector<Eigen::Vector2d> mid;
  mid.reserve(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector2d q = point_at_arc(a.polyline, s0 + (s1 - s0) * i / n);
    const PolylineProjection pb = project_on_polyline(b.polyline, q);
    mid.push_back(0.5 * (q + pb.foot(q)));
  }
  return mid;
}

}  // namespace

PolylineProjection project_on_polyline(const std::vector<Eigen::Vector2d>& line,
                                       const Eigen::Vector2d& p) {
  PolylineProjection best;
  if (line.empty()) return best;
  best.point = line.front();
  best.distance = (p - line.front()).norm();
  double best_d2 = std::numeric_limits<double>::infinity(), arc = 0.0, best_t = 0.0;
  double best_arc = 0.0;
  const int last = static_cast<int>(line.size()) - 2;
  for (int i = 0; i <= last; ++i) {
    const Eigen::Vector2d d = line[i + 1] - line[i];
    const double l2 = d.squaredNorm();
    if (l2 <= 0.0) continue;
    const double t = std::clamp((p - line[i]).dot(d) / l2, 0.0, 1.0);
    const double d2 = (p - (line[i] + t * d)).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best.segment = i;
      best_t = t;
      best_arc = arc;
    }
    arc += std::sqrt(l2);
  }
  best.length = arc;
  if (!std::isfinite(best_d2)) return best;
  const int i = best.segment;
  const Eigen::Vector2d d = line[i + 1] - line[i];
  const double l = d.norm();
  const Eigen::Vector2d u = d / l;
  best.point = line[i] + best_t * d;
  best.distance = std::sqrt(best_d2);
  best.tangent = u;
  // At an interior vertex the bisector of the two segments is the tangent.
  if (best_t <= 0.0 && i > 0)
    best.tangent = (u + (line[i] - line[i - 1]).normalized()).normalized();
  if (best_t >= 1.0 && i < last)
    best.tangent = (u + (line[i + 2] - line[i + 1]).normalized()).normalized();
  const double raw_t = (p - line[i]).dot(u);
  const bool before = i == 0 && raw_t < 0.0, after = i == last && raw_t > l;
  best.along = best_arc + ((before || after) ? raw_t : best_t * l);
  if (before || after) {
    best.tangent = u;
    best.lateral = cross(u, p - line[i]);
  } else {
    const double c = cross(best.tangent, p - best.point);
    best.lateral = c >= 0.0 ? best.distance : -best.distance;
  }
  return best;
}

FieldTruth::FieldTruth(const Field& field) : field_(&field) {
  std::map<int, Block> by_id;
  for (std::size_t i = 0; i < field.rows.size(); ++i) {
    Block& b = by_id[field.rows[i].block];
    b.id = field.rows[i].block;
    b.rows.push_back(static_cast<int>(i));
  }
  for (auto& [id, b] : by_id) {
    for (std::size_t k = 0; k + 1 < b.rows.size(); ++k)
      b.corridors.push_back(corridor_midline(field.rows[b.rows[k]], field.rows[b.rows[k + 1]]));
    blocks_.push_back(std::move(b));
  }
}

const FieldTruth::Block* FieldTruth::find_block(int id) const {
  for (const auto& b : blocks_)
    if (b.id == id) return &b;
  return nullptr;
}

const std::vector<Eigen::Vector2d>& FieldTruth::corridor_centre(int block, int k) const {
  static const std::vector<Eigen::Vector2d> kEmpty;
  const Block* b = find_block(block);
  if (b == nullptr || k < 0 || k >= static_cast<int>(b->corridors.size())) return kEmpty;
  return b->corridors[static_cast<std::size_t>(k)];
}

int FieldTruth::corridor_count(int block) const {
  const Block* b = find_block(block);
  return b == nullptr ? 0 : static_cast<int>(b->corridors.size());
}

std::vector<int> FieldTruth::blocks() const {
  std::vector<int> ids;
  for (const auto& b : blocks_) ids.push_back(b.id);
  return ids;
}

const std::vector<int>& FieldTruth::block_rows(int block) const {
  static const std::vector<int> kEmpty;
  const Block* b = find_block(block);
  return b == nullptr ? kEmpty : b->rows;
}

GroundTruth FieldTruth::at(const core::Pose2& T, double stamp, double reach) const {
  GroundTruth gt;
  gt.stamp = stamp;
  gt.T_world_base = T;
  const Eigen::Vector2d p = T.translation();
  if (blocks_.empty() || !p.allFinite()) return gt;
  std::vector<PolylineProjection> proj(field_->rows.size());
  int nearest = 0;
  for (std::size_t i = 0; i < proj.size(); ++i) {
    proj[i] = project_on_polyline(field_->rows[i].polyline, p);
    if (proj[i].distance < proj[static_cast<std::size_t>(nearest)].distance)
      nearest = static_cast<int>(i);
  }
  gt.block = field_->rows[static_cast<std::size_t>(nearest)].block;
  fill_place(*find_block(gt.block), T, proj, gt);
  fill_rows(T, reach, proj, gt);
  return gt;
}

}  // namespace rownav::sim
