#pragma once
/// @file height_band.hpp Keeps points whose height above the estimated ground lies in a band
/// (Nehme 2021 sec. 4 and Bertoglio 2023 sec. II-A height thresholding, made ground-relative so
/// that sloped fields work).
#include <span>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/preprocess/cropped_point.hpp"
#include "rownav/preprocess/ground.hpp"

namespace rownav::preprocess {

/// Height band above the ground.
struct HeightBandConfig {
  double min_height = 0.2;  ///< [m] above ground: drops the ground, its roughness and grass
  double max_height = 3.0;  ///< [m] above ground: drops overhanging branches, birds, wires above

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("min_height", s.min_height);
    v("max_height", s.max_height);
  }
  void validate() const;
};

/// Appends to `out` (cleared first) the points with min_height <= ground.height(p) <= max_height.
void height_band(std::span<const core::PointXYZIRT> in, const GroundEstimator& ground,
                 const HeightBandConfig& config, std::vector<core::PointXYZIRT>& out);

/// The same band on cropped points, into out[0, returned count) in order (`out` is only grown,
/// never shrunk or initialised): a branch-free compaction, since whether a return is in the band
/// changes from one return to the next along a column.
std::size_t height_band(std::span<const CroppedPoint> in, const GroundEstimator& ground,
                        const HeightBandConfig& config, std::vector<CroppedPoint>& out);

}  // namespace rownav::preprocess
