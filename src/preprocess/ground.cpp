// Ground estimation: lowest-cell grid with a robust plane and hole filling, or a RANSAC plane.
#include "rownav/preprocess/ground.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "rownav/core/angle.hpp"
#include "rownav/preprocess/cell_hash.hpp"

namespace rownav::preprocess {

namespace {

constexpr int kMaxGridCells = 128 * 128;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/// Least-squares z = c0 + c1 x + c2 y over the points within `threshold` (perpendicular) of the
/// plane n.p + d = 0. False when the normal equations are singular.
bool refine_plane(std::span<const Eigen::Vector3f> pts, const Eigen::Vector3d& n, double d,
                  double threshold, GroundPlane& out, std::size_t& count) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  count = 0;
  for (const auto& p : pts) {
    const Eigen::Vector3d q = p.cast<double>();
    if (std::abs(n.dot(q) + d) > threshold) continue;
    const Eigen::Vector3d r(1.0, q.x(), q.y());
    A += r * r.transpose();
    b += r * q.z();
    ++count;
  }
  if (count < 3) return false;
  Eigen::LDLT<Eigen::Matrix3d> ldlt(A);
  if (ldlt.info() != Eigen::Success || std::abs(A.determinant()) < 1e-9) return false;
  out = ldlt.solve(b);
  return out.allFinite();
}

}  // namespace

void GroundConfig::validate() const {
  core::check(std::isfinite(flat_z), "flat_z", "must be finite");
  core::check_positive(cell_size, "cell_size");
  core::check_range(percentile, 0.0, 1.0, "percentile");
  core::check_positive(min_cell_points, "min_cell_points");
  core::check_positive(max_residual, "max_residual");
  core::check_range(max_slope_deg, 0.0, 89.0, "max_slope_deg");
  core::check_positive(ransac_iterations, "ransac_iterations");
  core::check_positive(ransac_threshold, "ransac_threshold");
  core::check(max_points >= 3, "max_points", "must be >= 3");
}

bool ransac_plane(std::span<const Eigen::Vector3f> pts, int iterations, double threshold,
                  double max_slope_deg, std::mt19937_64& rng, GroundPlane& plane,
                  std::size_t* inliers) {
  const std::size_t n = pts.size();
  if (n < 3) return false;
  const double cos_max = std::cos(core::deg2rad(max_slope_deg));
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  std::size_t best = 0;
  Eigen::Vector3d best_n = Eigen::Vector3d::UnitZ();
  double best_d = 0.0;
  for (int it = 0; it < iterations; ++it) {
    const std::size_t i = pick(rng), j = pick(rng), k = pick(rng);
    if (i == j || j == k || i == k) continue;
    const Eigen::Vector3d a = pts[i].cast<double>();
    Eigen::Vector3d nrm = (pts[j].cast<double>() - a).cross(pts[k].cast<double>() - a);
    const double len = nrm.norm();
    if (len < 1e-9) continue;
    nrm /= len;
    if (nrm.z() < 0.0) nrm = -nrm;
    if (nrm.z() < cos_max) continue;  // steeper than the slope limit: a hedge, a wall
    const double d = -nrm.dot(a);
    std::size_t count = 0;
    for (const auto& p : pts) count += std::abs(nrm.dot(p.cast<double>()) + d) <= threshold;
    if (count > best) {
      best = count;
      best_n = nrm;
      best_d = d;
    }
  }
  if (best < 3) return false;
  GroundPlane refined;
  std::size_t count = best;
  if (!refine_plane(pts, best_n, best_d, threshold, refined, count) ||
      std::hypot(refined[1], refined[2]) > std::tan(core::deg2rad(max_slope_deg)))
    refined = GroundPlane(-best_d / best_n.z(), -best_n.x() / best_n.z(), -best_n.y() / best_n.z());
  plane = refined;
  if (inliers) *inliers = count;
  return true;
}

GroundEstimator::GroundEstimator(const GroundConfig& config) : config_(config) {
  config_.validate();
  set_flat();
}

void GroundEstimator::set_flat() {
  method_ = GroundMethod::none;
  plane_ = GroundPlane(config_.flat_z, 0.0, 0.0);
  pc_ = {static_cast<float>(config_.flat_z), 0.0f, 0.0f};
}

bool GroundEstimator::estimate(std::span<const core::PointXYZIRT> points) {
  return estimate_any(points);
}

bool GroundEstimator::estimate(std::span<const CroppedPoint> points) {
  return estimate_any(points);
}

// Templated on the point type (PointXYZIRT, CroppedPoint): only x, y, z are read.
template <class P>
bool GroundEstimator::estimate_any(std::span<const P> points) {
  set_flat();
  rng_.seed(config_.seed);
  if (config_.method == GroundMethod::none) return true;
  if (config_.method == GroundMethod::lowest_cell) return estimate_cells(points);
  // RANSAC on a strided subset (deterministic, spread over the whole frame).
  sample_.clear();
  for (std::size_t i = 0; i < points.size(); i += stride(points.size()))
    sample_.emplace_back(points[i].x, points[i].y, points[i].z);
  GroundPlane p;
  if (!ransac_plane(sample_, config_.ransac_iterations, config_.ransac_threshold,
                    config_.max_slope_deg, rng_, p))
    return false;
  plane_ = p;
  pc_ = {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
  method_ = GroundMethod::ransac_plane;
  return true;
}

template <class P>
void GroundEstimator::setup_grid(std::span<const P> points, std::size_t step) {
  float x0 = points[0].x, x1 = x0, y0 = points[0].y, y1 = y0;
  for (std::size_t i = 0; i < points.size(); i += step) {
    const auto& p = points[i];
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  cell_ = static_cast<float>(config_.cell_size);
  while (true) {  // grow cells until the grid is small enough (huge uncropped frames)
    nx_ = static_cast<int>((x1 - x0) / cell_) + 1;
    ny_ = static_cast<int>((y1 - y0) / cell_) + 1;
    if (static_cast<long>(nx_) * ny_ <= kMaxGridCells) break;
    cell_ *= 2.0f;
  }
  gx0_ = x0, gy0_ = y0, inv_cell_ = 1.0f / cell_;
}

template <class P>
bool GroundEstimator::estimate_cells(std::span<const P> points) {
  if (points.size() < static_cast<std::size_t>(config_.min_cell_points)) return false;
  const std::size_t step = stride(points.size()), m = (points.size() + step - 1) / step;
  setup_grid(points, step);
  const std::size_t cells = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  // Counting sort of z by cell, then a per-cell quantile (nth_element).
  start_.assign(cells + 1, 0);
  cell_of_.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    const auto& p = points[i * step];
    const int ix = std::min(nx_ - 1, static_cast<int>((p.x - gx0_) * inv_cell_));
    const int iy = std::min(ny_ - 1, static_cast<int>((p.y - gy0_) * inv_cell_));
    cell_of_[i] = static_cast<std::uint32_t>(iy * nx_ + ix);
    ++start_[cell_of_[i] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  zbuf_.resize(m);
  for (std::size_t i = 0; i < m; ++i) zbuf_[start_[cell_of_[i]]++] = points[i * step].z;
  for (std::size_t c = cells; c > 0; --c) start_[c] = start_[c - 1];  // cursors -> begins
  start_[0] = 0;
  cell_z_.assign(cells, kNaN);
  sample_.clear();
  for (std::size_t c = 0; c < cells; ++c) {
    const std::size_t s = start_[c], n = start_[c + 1] - s;
    if (n < static_cast<std::size_t>(config_.min_cell_points)) continue;
    const auto k = static_cast<std::size_t>(config_.percentile * static_cast<double>(n - 1));
    std::nth_element(zbuf_.begin() + s, zbuf_.begin() + s + k, zbuf_.begin() + s + n);
    cell_z_[c] = zbuf_[s + k];
    sample_.emplace_back(gx0_ + (static_cast<float>(c % nx_) + 0.5f) * cell_,
                         gy0_ + (static_cast<float>(c / nx_) + 0.5f) * cell_, cell_z_[c]);
  }
  if (sample_.empty()) return false;
  GroundPlane p(sample_[0].z(), 0.0, 0.0);
  if (sample_.size() >= 3 &&
      !ransac_plane(sample_, config_.ransac_iterations, config_.max_residual,
                    config_.max_slope_deg, rng_, p))
    return false;  // every cell hypothesis too steep: do not trust the grid
  plane_ = p;
  pc_ = {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
  fill_holes();
  method_ = GroundMethod::lowest_cell;
  return true;
}

void GroundEstimator::fill_holes() {
  const auto centre_plane = [&](int ix, int iy) {
    return plane_z(gx0_ + (static_cast<float>(ix) + 0.5f) * cell_,
                   gy0_ + (static_cast<float>(iy) + 0.5f) * cell_);
  };
  const float tol = static_cast<float>(config_.max_residual);
  // Cells far from the robust plane only saw canopy (or a pit): holes.
  for (int iy = 0; iy < ny_; ++iy)
    for (int ix = 0; ix < nx_; ++ix) {
      float& z = cell_z_[static_cast<std::size_t>(iy * nx_ + ix)];
      if (!std::isnan(z) && std::abs(z - centre_plane(ix, iy)) > tol) z = kNaN;
    }
  filled_.resize(cell_z_.size());
  for (int iy = 0; iy < ny_; ++iy)
    for (int ix = 0; ix < nx_; ++ix) {
      const auto c = static_cast<std::size_t>(iy * nx_ + ix);
      if (!std::isnan(cell_z_[c])) {
        filled_[c] = cell_z_[c] - centre_plane(ix, iy);
        continue;
      }
      float sum = 0.0f;  // mean residual of the valid 8-neighbours, on top of the plane
      int n = 0;
      for (int jy = std::max(0, iy - 1); jy <= std::min(ny_ - 1, iy + 1); ++jy)
        for (int jx = std::max(0, ix - 1); jx <= std::min(nx_ - 1, ix + 1); ++jx) {
          const float z = cell_z_[static_cast<std::size_t>(jy * nx_ + jx)];
          if (std::isnan(z)) continue;
          sum += z - centre_plane(jx, jy);
          ++n;
        }
      filled_[c] = n > 0 ? sum / static_cast<float>(n) : 0.0f;
    }
}

}  // namespace rownav::preprocess
