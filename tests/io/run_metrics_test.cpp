#include "rownav/io/run_metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rownav::io {
namespace {

TEST(RunMetrics, PathLengthRatioOfStraightRunIsOneAndOfSinusoidMore) {
  std::vector<Eigen::Vector2d> ref{{0, 0}, {20, 0}}, straight, wave;
  for (int i = 0; i <= 200; ++i) {
    straight.emplace_back(i * 0.1, 0.0);
    wave.emplace_back(i * 0.1, 0.3 * std::sin(i * 0.1));
  }
  EXPECT_NEAR(*path_length_ratio(straight, ref), 1.0, 1e-9);
  EXPECT_GT(*path_length_ratio(wave, ref), 1.01);
  EXPECT_FALSE(path_length_ratio({{0, 0}, {0.5, 0}}, ref).has_value());
}

}  // namespace
}  // namespace rownav::io
