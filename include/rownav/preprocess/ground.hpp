#pragma once
/// @file ground.hpp Per-frame ground estimate, so that height thresholds (Nehme 2021 sec. 4,
/// Bertoglio 2023 sec. II-A) hold on sloped and uneven fields: a lowest-cell grid (low percentile
/// of z per cell, made robust by a plane fit over the cells, holes filled from neighbours or the
/// plane) or a seeded RANSAC plane.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/preprocess/cropped_point.hpp"

namespace rownav::preprocess {

/// How the ground is estimated.
enum class GroundMethod : std::uint8_t {
  none,          ///< flat ground at GroundConfig::flat_z (base frame)
  lowest_cell,   ///< grid of low z percentiles, robust plane, holes filled
  ransac_plane   ///< a single plane by RANSAC, refined by least squares on its inliers
};

/// Ground estimation parameters.
struct GroundConfig {
  GroundMethod method = GroundMethod::lowest_cell;  ///< estimator
  double flat_z = 0.0;  ///< [m] ground z in the base frame for `none` and when estimation fails
  double cell_size = 1.0;     ///< [m] lowest_cell grid edge (grown if the grid exceeds 128 x 128)
  double percentile = 0.05;   ///< [-] z quantile taken as the ground of a cell (low: robust to
                              ///< canopy, above the lowest noisy return)
  int min_cell_points = 4;    ///< [-] fewer points: the cell is a hole
  double max_residual = 0.3;  ///< [m] lowest_cell: a cell farther from the plane fit is a hole
                              ///< (canopy-only cells); ransac_plane: not used
  double max_slope_deg = 20.0;      ///< [deg] steeper plane hypotheses are rejected
  int ransac_iterations = 100;      ///< [-] plane hypotheses (ransac_plane; lowest_cell on cells)
  double ransac_threshold = 0.08;   ///< [m] inlier distance to the plane (ransac_plane)
  int max_points = 8192;  ///< [-] the estimate uses a strided subset of at most this many points
  std::uint64_t seed = 1;           ///< RANSAC seed, re-applied every frame (same frame, same plane)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("method", s.method);
    v("flat_z", s.flat_z);
    v("cell_size", s.cell_size);
    v("percentile", s.percentile);
    v("min_cell_points", s.min_cell_points);
    v("max_residual", s.max_residual);
    v("max_slope_deg", s.max_slope_deg);
    v("ransac_iterations", s.ransac_iterations);
    v("ransac_threshold", s.ransac_threshold);
    v("max_points", s.max_points);
    v("seed", s.seed);
  }
  void validate() const;
};

/// Ground plane z = c[0] + c[1] x + c[2] y.
using GroundPlane = Eigen::Vector3d;

/// Fits a plane to `pts` (x, y, z) by RANSAC with a slope limit, then least squares on the
/// inliers. Returns false (plane untouched) when no hypothesis is acceptable. Deterministic for
/// a given rng state. `inliers` receives the final inlier count.
bool ransac_plane(std::span<const Eigen::Vector3f> pts, int iterations, double threshold,
                  double max_slope_deg, std::mt19937_64& rng, GroundPlane& plane,
                  std::size_t* inliers = nullptr);

/// Per-frame ground estimate; ground_z / height are the height-above-ground function.
/// Buffers are reused across frames; estimate() never throws.
class GroundEstimator {
 public:
  explicit GroundEstimator(const GroundConfig& config = {});
  /// Estimates the ground from a cloud (base frame, finite points). False when the method
  /// failed (too few points / no acceptable plane): the ground is then flat at flat_z.
  bool estimate(std::span<const core::PointXYZIRT> points);
  /// The same estimate from cropped points (the same coordinates give the same ground).
  bool estimate(std::span<const CroppedPoint> points);
  /// [m] ground z at (x, y), base frame.
  float ground_z(float x, float y) const {
    return method_ == GroundMethod::lowest_cell ? grid_z(x, y) : plane_z(x, y);
  }
  /// [m] height of p above the ground.
  float height(const core::PointXYZIRT& p) const { return p.z - ground_z(p.x, p.y); }
  /// The plane (RANSAC, or the lowest_cell robust plane); flat_z when estimation failed.
  const GroundPlane& plane() const { return plane_; }
  const GroundConfig& config() const { return config_; }

 private:
  float plane_z(float x, float y) const { return pc_[0] + pc_[1] * x + pc_[2] * y; }
  /// The plane plus the residual of the nearest cell (exact on a plane, no bilinear cost).
  float grid_z(float x, float y) const {
    const int ix = std::clamp(static_cast<int>((x - gx0_) * inv_cell_), 0, nx_ - 1);
    const int iy = std::clamp(static_cast<int>((y - gy0_) * inv_cell_), 0, ny_ - 1);
    return plane_z(x, y) + filled_[static_cast<std::size_t>(iy * nx_ + ix)];
  }
  template <class P>
  bool estimate_any(std::span<const P> points);
  template <class P>
  bool estimate_cells(std::span<const P> points);
  template <class P>
  void setup_grid(std::span<const P> points, std::size_t step);
  void fill_holes();
  void set_flat();
  std::size_t stride(std::size_t n) const {
    const auto m = static_cast<std::size_t>(config_.max_points);
    return std::max<std::size_t>(1, (n + m - 1) / m);
  }

  GroundConfig config_;
  GroundMethod method_ = GroundMethod::none;  // effective method of the last estimate
  GroundPlane plane_ = GroundPlane::Zero();
  std::array<float, 3> pc_{0.0f, 0.0f, 0.0f};
  std::mt19937_64 rng_;
  // lowest_cell grid: origin, cell size, dimensions, per-cell ground z (NaN = hole)
  float gx0_ = 0.0f, gy0_ = 0.0f, cell_ = 1.0f, inv_cell_ = 1.0f;
  int nx_ = 0, ny_ = 0;
  std::vector<float> cell_z_, filled_, zbuf_;  // filled_: per-cell residual above the plane
  std::vector<std::uint32_t> cell_of_, start_;
  std::vector<Eigen::Vector3f> sample_;
};

}  // namespace rownav::preprocess

template <>
struct rownav::core::EnumNames<rownav::preprocess::GroundMethod> {
  using E = rownav::preprocess::GroundMethod;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::none, "none"}, {E::lowest_cell, "lowest_cell"}, {E::ransac_plane, "ransac_plane"}}};
};
