#include "rownav/preprocess/crop_box.hpp"

#include <algorithm>
#include <cmath>

namespace rownav::preprocess {

namespace {

/// Relative margin on the squared range of the box's farthest corner: covers the float rounding
/// of the bounds and of dx * dx + dy * dy (a few ulp, ~1e-6) many times over.
constexpr double kRingMargin = 1e-4;

}  // namespace

void CropBoxConfig::validate() const {
  core::check(x_min < x_max, "x_max", "must be > x_min");
  core::check(y_min < y_max, "y_max", "must be > y_min");
  core::check(z_min < z_max, "z_max", "must be > z_min");
  core::check_non_negative(range_min, "range_min");
  core::check(range_min < range_max, "range_max", "must be > range_min");
  core::check(sensor_xy.allFinite(), "sensor_xy", "must be finite");
}

CropBox::CropBox(const CropBoxConfig& config)
    : config_(config),
      x_min_(static_cast<float>(config.x_min)),
      x_max_(static_cast<float>(config.x_max)),
      y_min_(static_cast<float>(config.y_min)),
      y_max_(static_cast<float>(config.y_max)),
      z_min_(static_cast<float>(config.z_min)),
      z_max_(static_cast<float>(config.z_max)),
      sx_(static_cast<float>(config.sensor_xy.x())),
      sy_(static_cast<float>(config.sensor_xy.y())),
      r2_min_(static_cast<float>(config.range_min * config.range_min)),
      r2_max_(static_cast<float>(config.range_max * config.range_max)) {
  config_.validate();
  // With no minimum range and the farthest box corner well inside range_max, a point in the box
  // always passes the range test (exactly: its float r2 stays far below r2_max_).
  double far2 = 0.0;
  for (const double x : {config.x_min, config.x_max})
    for (const double y : {config.y_min, config.y_max})
      far2 = std::max(
          far2, std::pow(x - config.sensor_xy.x(), 2) + std::pow(y - config.sensor_xy.y(), 2));
  ring_test_ =
      config.range_min > 0.0 || far2 * (1.0 + kRingMargin) >= config.range_max * config.range_max;
}

std::size_t CropBox::crop(std::span<const core::PointXYZIRT> in, std::vector<CroppedPoint>& out,
                          std::size_t& invalid) const {
  if (out.size() < in.size()) out.resize(in.size());
  // Branches, not a branch-free compaction: a column's returns mostly share the outcome, and
  // computing every test costs more (bench/preprocess_bench.cpp). keeps() is false for NaN /
  // Inf, so only the dropped points are checked for them.
  std::size_t kept = 0, bad = 0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const auto& p = in[i];
    if (keeps(p.x, p.y, p.z))
      out[kept++] = {p.x, p.y, p.z, static_cast<std::uint32_t>(i)};
    else
      bad += !p.finite();
  }
  invalid = bad;
  return kept;
}

}  // namespace rownav::preprocess
