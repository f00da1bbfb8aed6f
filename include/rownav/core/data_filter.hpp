#pragma once
/// @file data_filter.hpp Malavazi 2018's data filter (004_1bee156ef8a2b3f7.txt sec. 2.3.1 and
/// 3.1.1): before the crop modelling, keep only the scan points inside an infinite-length box
/// around the last accepted model of each side; a side without a model (or with a steep one)
/// keeps its points 0.3-3 m from the robot. Weeds between the rows never reach the line fit.
/// The tracker that follows the models builds the boxes (track::RowTracker::data_filter), the
/// detection pipeline applies them (detect::DetectionPipeline::set_data_filter).
#include <Eigen/Core>
#include <array>
#include <optional>
#include <span>
#include <vector>

namespace rownav::core {

/// One side's followed model y = a x + b in the base frame of the frame to filter.
struct SideModel {
  double a = 0.0;  ///< [-] slope
  double b = 0.0;  ///< [m] intercept (lateral offset at the base)
};

/// The boxes of one frame.
struct DataFilterBoxes {
  /// [0] left (y > 0), [1] right (y < 0); nullopt: that side keeps its initialisation window.
  std::array<std::optional<SideModel>, 2> models;
  // Filled by the tracker from its config (track::ModelFilterConfig: box_half_width,
  // box_spacing_ratio, init_min_distance, init_max_distance); no defaults restated here.
  double half_width = 0.0;      ///< [m] box half width around a model
  double init_min_range = 0.0;  ///< [m] side without a model: nearest point kept (sec. 3.1.1)
  double init_max_range = 0.0;  ///< [m] side without a model: farthest point kept (ibid.)
};

/// The points of `points_base` the boxes keep (order preserved; non-finite points dropped).
/// Never throws.
std::vector<Eigen::Vector2f> filter_points(std::span<const Eigen::Vector2f> points_base,
                                           const DataFilterBoxes& boxes);

}  // namespace rownav::core
