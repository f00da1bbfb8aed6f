#pragma once
/// @file flat_ground.hpp Test helpers: a point, and a ground estimate of a flat floor at z = 0.
#include "rownav/core/point_cloud.hpp"
#include "rownav/preprocess/ground.hpp"

namespace rownav::test {

inline core::PointXYZIRT pt(float x, float y, float z) {
  core::PointXYZIRT p;
  p.x = x, p.y = y, p.z = z;
  return p;
}

/// Flat ground at z = 0: a lowest-cell grid over a floor of points, x in [-6, 8], |y| <= 3.
inline preprocess::GroundEstimator flat_ground() {
  std::vector<core::PointXYZIRT> floor;
  for (float x = -6.0f; x <= 8.0f; x += 0.25f)
    for (float y = -3.0f; y <= 3.0f; y += 0.25f) floor.push_back(pt(x, y, 0.0f));
  preprocess::GroundEstimator g;
  g.estimate(floor);
  return g;
}

}  // namespace rownav::test
