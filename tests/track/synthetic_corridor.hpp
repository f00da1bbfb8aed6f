#pragma once
// Synthetic row observations of straight parallel rows seen from a known pose: the truth for the
// tracker unit tests (rows along world x at y = (k + 0.5) * spacing, corridor centre y = 0).
#include <cmath>
#include <random>
#include <vector>

#include "rownav/core/pose2.hpp"
#include "rownav/core/row_observation.hpp"

namespace rownav::test {

struct CorridorScene {
  double spacing = 2.0;             // [m]
  int rows_each_side = 2;           // rows on each side of the corridor
  double noise_offset = 0.0;        // [m] std of a detected row's offset
  double noise_heading = 0.0;       // [rad] std of the detected heading
  double x_min = 0.5, x_max = 6.0;  // [m] support along x in the base frame
};

/// What a detector would report from T_world_base (rows sorted right to left).
inline core::RowObservation observe(const CorridorScene& s, const core::Pose2& T_world_base,
                                    double stamp, std::mt19937_64& rng) {
  std::normal_distribution<double> n_off(0.0, s.noise_offset > 0 ? s.noise_offset : 1e-12);
  std::normal_distribution<double> n_head(0.0, s.noise_heading > 0 ? s.noise_heading : 1e-12);
  const core::Pose2 T_base_world = T_world_base.inverse();
  core::RowObservation obs;
  obs.stamp = stamp;
  obs.status = core::DetectionStatus::ok;
  obs.confidence = 0.9;
  const double dh = n_head(rng);
  for (int k = -s.rows_each_side; k < s.rows_each_side; ++k) {
    const core::Line2 world({0.0, (k + 0.5) * s.spacing}, {1.0, 0.0});
    core::Line2 base = world.transformed(T_base_world);
    const double y0 = base.y_at(0.0) + n_off(rng);
    const double h = base.heading() + dh;
    core::RowLine r;
    r.line = core::Line2({0.0, y0}, {std::cos(h), std::sin(h)});
    r.offset = y0;
    r.heading = h;
    r.x_min = s.x_min, r.x_max = s.x_max;
    r.support = 100;
    obs.rows.push_back(r);
  }
  std::sort(obs.rows.begin(), obs.rows.end(),
            [](const core::RowLine& a, const core::RowLine& b) { return a.offset < b.offset; });
  for (int i = 0; i < static_cast<int>(obs.rows.size()); ++i) {
    if (obs.rows[std::size_t(i)].offset < 0) obs.right = i;
    if (obs.rows[std::size_t(i)].offset >= 0 && obs.left < 0) obs.left = i;
  }
  obs.heading = obs.rows.front().heading;
  return obs;
}

/// A frame without rows.
inline core::RowObservation blank(double stamp) {
  core::RowObservation obs;
  obs.stamp = stamp;
  return obs;
}

}  // namespace rownav::test
