#pragma once
/// @file point_labeller.hpp Semantic labels of laser points (Emmi 2021, 002_806e72d300173f73.txt,
/// sec. "Perception": only the points of the target crop describe the field structure).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"

namespace rownav::map {

/// Class of one laser point.
enum class PointLabel : std::uint8_t {
  crop,        ///< the target crop of this field (rows the map is built from)
  other_crop,  ///< a crop of a neighbouring field (Emmi 2021: "isolate one field from another")
  weed,        ///< weeds, grass
  obstacle,    ///< anything else standing (posts of other fields, people, machines)
  ground       ///< the ground
};

/// Gives every laser point a class: the simulator's ground truth (sim/truth_labeller.hpp) or a
/// camera-based detector (Emmi 2021 Fig. 2b). Implementations never throw from label().
class PointLabeller {
 public:
  virtual ~PointLabeller() = default;
  /// Labels `points_base` (base frame, x forward, y left, z up) into `labels` (resized to the
  /// same count). Non-finite points may get any label; the map stage drops them.
  virtual void label(const std::vector<Eigen::Vector3f>& points_base,
                     std::vector<PointLabel>& labels) = 0;
};

}  // namespace rownav::map

template <>
struct rownav::core::EnumNames<rownav::map::PointLabel> {
  using E = rownav::map::PointLabel;
  static constexpr std::array<std::pair<E, std::string_view>, 5> values{
      {{E::crop, "crop"}, {E::other_crop, "other_crop"}, {E::weed, "weed"},
       {E::obstacle, "obstacle"}, {E::ground, "ground"}}};
};
