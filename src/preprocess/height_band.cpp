#include "rownav/preprocess/height_band.hpp"

#include <cmath>

namespace rownav::preprocess {

void HeightBandConfig::validate() const {
  core::check(std::isfinite(min_height), "min_height", "must be finite");
  core::check(std::isfinite(max_height) && min_height < max_height, "max_height",
              "must be finite and > min_height");
}

void height_band(std::span<const core::PointXYZIRT> in, const GroundEstimator& ground,
                 const HeightBandConfig& config, std::vector<core::PointXYZIRT>& out) {
  out.clear();
  const auto lo = static_cast<float>(config.min_height);
  const auto hi = static_cast<float>(config.max_height);
  for (const auto& p : in) {
    const float h = ground.height(p);
    if (h >= lo && h <= hi) out.push_back(p);
  }
}

std::size_t height_band(std::span<const CroppedPoint> in, const GroundEstimator& ground,
                        const HeightBandConfig& config, std::vector<CroppedPoint>& out) {
  if (out.size() < in.size()) out.resize(in.size());
  const auto lo = static_cast<float>(config.min_height);
  const auto hi = static_cast<float>(config.max_height);
  std::size_t kept = 0;
  for (const auto& p : in) {
    const float h = p.z - ground.ground_z(p.x, p.y);  // ground.height() of the cloud point
    out[kept] = p;
    kept += (h >= lo) & (h <= hi);
  }
  return kept;
}

}  // namespace rownav::preprocess
