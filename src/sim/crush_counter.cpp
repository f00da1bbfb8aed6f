/// @file crush_counter.cpp Plants run over by the robot footprint, on a uniform grid.
#include <algorithm>
#include <cmath>

#include "rownav/sim/field_truth.hpp"

namespace rownav::sim {
namespace {

constexpr double kMaxCells = 4.0e6;  // bound on grid memory for very large fields

bool crushable(PlantKind k) {
  return k == PlantKind::vine || k == PlantKind::tree || k == PlantKind::crop;
}

/// True when the circle (c, r) intersects the convex quad q (either winding).
bool circle_hits_quad(const Eigen::Vector2d& c, double r, const std::array<Eigen::Vector2d, 4>& q) {
  bool pos = true, neg = true;
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector2d a = q[i], b = q[(i + 1) % 4], d = b - a;
    const double cr = d.x() * (c.y() - a.y()) - d.y() * (c.x() - a.x());
    pos = pos && cr >= 0.0;
    neg = neg && cr <= 0.0;
    const double l2 = d.squaredNorm();
    const double t = l2 > 0.0 ? std::clamp((c - a).dot(d) / l2, 0.0, 1.0) : 0.0;
    if ((c - (a + t * d)).squaredNorm() <= r * r) return true;
  }
  return pos || neg;  // centre inside
}

}  // namespace

CrushCounter::CrushCounter(const Field& field) {
  Eigen::AlignedBox2d box;
  for (std::size_t i = 0; i < field.plants.size(); ++i) {
    const Plant& p = field.plants[i];
    if (!crushable(p.kind) || !p.position.allFinite()) continue;
    centres_.push_back(p.position);
    radii_.push_back(std::max(0.0, p.radius));
    plant_index_.push_back(static_cast<int>(i));
    max_radius_ = std::max(max_radius_, radii_.back());
    box.extend(p.position);
  }
  done_.assign(centres_.size(), false);
  if (centres_.empty()) return;
  origin_ = box.min();
  const Eigen::Vector2d size = box.sizes() + Eigen::Vector2d::Constant(1e-6);
  cell_ = std::max(1.0, std::sqrt(size.x() * size.y() / kMaxCells));
  nx_ = static_cast<int>(size.x() / cell_) + 1;
  ny_ = static_cast<int>(size.y() / cell_) + 1;
  std::vector<int> cell_of(centres_.size());
  cell_start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  for (std::size_t i = 0; i < centres_.size(); ++i) {
    const Eigen::Vector2d g = (centres_[i] - origin_) / cell_;
    cell_of[i] = static_cast<int>(g.y()) * nx_ + static_cast<int>(g.x());
    ++cell_start_[static_cast<std::size_t>(cell_of[i]) + 1];
  }
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_items_.resize(centres_.size());
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < centres_.size(); ++i)
    cell_items_[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell_of[i])]++)] =
        static_cast<int>(i);
}

int CrushCounter::update(const std::array<Eigen::Vector2d, 4>& fp) {
  if (centres_.empty()) return 0;
  Eigen::AlignedBox2d box;
  for (const auto& c : fp) {
    if (!c.allFinite()) return 0;
    box.extend(c);
  }
  const Eigen::Vector2d lo = (box.min() - origin_).array() - max_radius_;
  const Eigen::Vector2d hi = (box.max() - origin_).array() + max_radius_;
  const auto cell = [&](double v, int n) {
    return static_cast<int>(std::clamp(std::floor(v / cell_), -1.0, static_cast<double>(n)));
  };
  const int x0 = std::max(0, cell(lo.x(), nx_)), x1 = std::min(nx_ - 1, cell(hi.x(), nx_));
  const int y0 = std::max(0, cell(lo.y(), ny_)), y1 = std::min(ny_ - 1, cell(hi.y(), ny_));
  int added = 0;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const auto c = static_cast<std::size_t>(y * nx_ + x);
      for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
        const auto i = static_cast<std::size_t>(cell_items_[static_cast<std::size_t>(k)]);
        if (done_[i] || !circle_hits_quad(centres_[i], radii_[i], fp)) continue;
        done_[i] = true;
        crushed_.push_back(plant_index_[i]);
        ++added;
      }
    }
  return added;
}

}  // namespace rownav::sim
