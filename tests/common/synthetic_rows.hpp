#pragma once
// Synthetic 2D row scenes with known ground truth, for the detector tests: parallel rows with a
// heading, canopy width (points spread across the row), gaps, weeds between rows, outliers and
// range noise. Points are in the robot frame (x forward, y left).
#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

#include "rownav/core/line2.hpp"

namespace rownav::test {

struct SyntheticRows {
  int rows = 4;                  // rows, placed symmetrically about the robot unless offset set
  double spacing = 1.8;          // [m]
  double offset = 0.0;           // [m] shift of the whole pattern across the rows (robot off-centre)
                                 //     offset and spacing are perpendicular to the rows
  double heading = 0.0;          // [rad] row heading in the robot frame
  double x_min = 0.3, x_max = 8.0;  // [m] visible extent along the rows
  double canopy_half_width = 0.15;  // [m] points spread uniformly across the row
  double point_spacing = 0.05;   // [m] along the row
  double noise = 0.01;           // [m] gaussian on both coordinates
  double gap_probability = 0.0;  // chance that a 1 m stretch of a row is missing
  int weeds = 0;                 // weed points uniformly in the corridors' middle third
  int outliers = 0;              // points uniformly in the box
  std::uint64_t seed = 1;
};

struct SyntheticScene {
  std::vector<Eigen::Vector2f> points;
  std::vector<core::Line2> truth;  // row centre lines, right to left
};

// Row k centre line: offset + (k - (rows - 1) / 2) * spacing at x = 0, rotated by heading.
inline SyntheticScene make_rows(const SyntheticRows& s) {
  std::mt19937_64 rng(s.seed);
  std::normal_distribution<double> n(0.0, s.noise);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  SyntheticScene scene;
  const Eigen::Vector2d dir(std::cos(s.heading), std::sin(s.heading));
  const Eigen::Vector2d left(-dir.y(), dir.x());
  for (int k = 0; k < s.rows; ++k) {
    const double y0 = s.offset + (k - 0.5 * (s.rows - 1)) * s.spacing;
    const Eigen::Vector2d p0(0.0, y0 / std::cos(s.heading));
    scene.truth.emplace_back(p0, dir);
    bool in_gap = false;
    for (double t = s.x_min; t <= s.x_max; t += s.point_spacing) {
      if (std::fmod(t, 1.0) < s.point_spacing) in_gap = u(rng) < s.gap_probability;
      if (in_gap) continue;
      const double across = (2.0 * u(rng) - 1.0) * s.canopy_half_width;
      const Eigen::Vector2d p = p0 + t * dir + across * left + Eigen::Vector2d(n(rng), n(rng));
      scene.points.push_back(p.cast<float>());
    }
  }
  for (int i = 0; i < s.weeds; ++i) {
    const int k = static_cast<int>(u(rng) * (s.rows - 1));
    const double y0 = s.offset + (k + 0.5 - 0.5 * (s.rows - 1)) * s.spacing;
    const double t = s.x_min + u(rng) * (s.x_max - s.x_min);
    const double across = (u(rng) - 0.5) * s.spacing / 3.0;
    const Eigen::Vector2d p = Eigen::Vector2d(0.0, y0) + t * dir + across * left;
    scene.points.push_back(p.cast<float>());
  }
  const double half = 0.5 * s.rows * s.spacing + 1.0;
  for (int i = 0; i < s.outliers; ++i)
    scene.points.emplace_back(static_cast<float>(s.x_min + u(rng) * (s.x_max - s.x_min)),
                              static_cast<float>((2.0 * u(rng) - 1.0) * half));
  return scene;
}

}  // namespace rownav::test
