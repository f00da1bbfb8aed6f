#pragma once
// Synthetic scenes for the map tests: straight rows of round plants seen by an ideal planar
// scanner (points on the side of each plant facing the robot, no occlusion), with known row
// ends, and a driver that feeds a PlaceEstimator along a polyline path.
#include <Eigen/Core>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "rownav/core/pose2.hpp"
#include "rownav/map/place_estimator.hpp"

namespace rownav::map::test {

struct SynthRow {
  double y = 0.0;                // [m] world y of the row line
  double x0 = 0.0, x1 = 10.0;    // [m] first / last plant
  PointLabel label = PointLabel::crop;
  std::vector<std::pair<double, double>> gaps;  // [m] x intervals without plants
};

struct SynthScene {
  std::vector<SynthRow> rows;
  double plant_spacing = 0.3;   // [m]
  double plant_radius = 0.12;   // [m]
  double range = 4.0;           // [m] scanner reach
  double noise = 0.01;          // [m] point noise
};

struct Frame {
  std::vector<Eigen::Vector3f> points;
  std::vector<PointLabel> labels;
};

/// Points within range, in the base frame, with their labels.
inline Frame scan(const SynthScene& s, const core::Pose2& T_world_base, std::mt19937_64& rng) {
  Frame f;
  std::normal_distribution<double> n(0.0, s.noise);
  const core::Pose2 T_base_world = T_world_base.inverse();
  for (const auto& row : s.rows) {
    for (double x = row.x0; x <= row.x1 + 1e-9; x += s.plant_spacing) {
      bool in_gap = false;
      for (const auto& [g0, g1] : row.gaps) in_gap = in_gap || (x > g0 && x < g1);
      if (in_gap) continue;
      const Eigen::Vector2d c(x, row.y);
      const Eigen::Vector2d to_robot = T_world_base.translation() - c;
      if (to_robot.norm() > s.range) continue;
      const double a0 = std::atan2(to_robot.y(), to_robot.x());
      for (int k = -2; k <= 2; ++k) {  // five points on the facing side of the plant
        const double a = a0 + 0.35 * k;
        const Eigen::Vector2d w = c + s.plant_radius * Eigen::Vector2d(std::cos(a), std::sin(a)) +
                                  Eigen::Vector2d(n(rng), n(rng));
        const Eigen::Vector2d b = T_base_world * w;
        f.points.emplace_back(static_cast<float>(b.x()), static_cast<float>(b.y()), 0.2f);
        f.labels.push_back(row.label);
      }
    }
  }
  return f;
}

/// Rows of a block: `lanes` lanes of `width` between rows from x0 to x1, row 0 at y = 0.
inline std::vector<SynthRow> block(int lanes, double width, double x0, double x1,
                                   PointLabel label = PointLabel::crop, double y0 = 0.0) {
  std::vector<SynthRow> rows;
  for (int i = 0; i <= lanes; ++i) rows.push_back({y0 + i * width, x0, x1, label, {}});
  return rows;
}

/// Poses every `step` metres along straight legs between waypoints (heading along each leg, or
/// the waypoint's theta for reversing legs when `reverse` is set on the target).
struct Waypoint {
  double x, y;
  bool reverse = false;  // drive backwards to this waypoint (heading kept)
};

inline std::vector<core::Pose2> path(const std::vector<Waypoint>& w, double step) {
  std::vector<core::Pose2> out;
  double heading = 0.0;
  for (std::size_t i = 1; i < w.size(); ++i) {
    const Eigen::Vector2d a(w[i - 1].x, w[i - 1].y), b(w[i].x, w[i].y);
    const Eigen::Vector2d d = b - a;
    if (!w[i].reverse) heading = std::atan2(d.y(), d.x());
    const int n = std::max(1, static_cast<int>(std::ceil(d.norm() / step)));
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector2d p = a + d * (static_cast<double>(k) / n);
      out.emplace_back(p.x(), p.y(), heading);
    }
  }
  return out;
}

/// Runs the estimator along the poses; returns every estimate.
inline std::vector<PlaceEstimate> drive(PlaceEstimator& est, const SynthScene& scene,
                                        const std::vector<core::Pose2>& poses,
                                        std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<PlaceEstimate> out;
  double t = 0.0;
  for (const auto& T : poses) {
    const Frame f = scan(scene, T, rng);
    out.push_back(est.update(f.points, f.labels, T, t));
    t += 0.1;
  }
  return out;
}

inline int count_transitions(const std::vector<PlaceEstimate>& e) {
  int n = 0;
  for (const auto& x : e) n += x.transition ? 1 : 0;
  return n;
}

}  // namespace rownav::map::test
