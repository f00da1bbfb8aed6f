#pragma once
/// @file place_input.hpp What NavStack hands the map stage (map::PlaceEstimator, Emmi 2021,
/// 002_806e72d300173f73.txt, Fig. 2a) in one frame: the points of a height band of the sweep
/// (Emmi 2021 used a planar laser scanner at the height of the trunks; the band stands for
/// that plane) with one label each.
///
/// Labels come with the cloud (NavStack::on_cloud's label vector: a camera detector as in
/// Emmi 2021 Fig. 2b, or the simulator's truth) or, when none were given, from the geometric
/// default: a point of the band within the half width of a row the detector found this frame
/// (its centre line +- RowLine::half_width + row_margin) is `crop`, every other point `ground`
/// (not a row: it never enters the map). The default cannot tell a row end pole from a plant
/// nor a neighbouring field from the target one (Emmi 2021's reason for semantic labels).
#include <Eigen/Core>
#include <optional>
#include <span>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/core/row_observation.hpp"
#include "rownav/map/place_estimator.hpp"
#include "rownav/map/point_labeller.hpp"
#include "rownav/preprocess/ground.hpp"

namespace rownav::navigate {

/// NavStack's map stage settings (the `place:` section of config/navigate/<crop>.yaml).
struct PlaceConfig {
  /// run the map stage every LiDAR frame (rownav: off by default until measured, issue 12)
  bool enabled = false;
  /// [m] height band above the local ground of the 3D points fed to the estimator: trunks and
  /// the low canopy of a vineyard (Emmi 2021: a planar scanner at trunk height), above the
  /// grass; a 2D scan is fed whole
  double band_z_min = 0.2;
  double band_z_max = 1.0;  ///< [m]
  /// [m] geometric default labels: a point this far beyond a detected row's half width (or its
  /// line when the half width is unknown) is still the row (rownav; vine shoots, point noise)
  double row_margin = 0.15;
  /// use the tracker's measured row spacing (status tracking, rows followed on both sides) as
  /// the lane width: estimator.key_locations.lane_width is only the a priori value until the
  /// tracker measured one (never a constant tuned to one field)
  bool lane_width_from_tracker = true;
  map::PlaceEstimatorConfig estimator;  ///< the map stage itself (map/place_estimator.hpp)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("enabled", s.enabled);
    v("band_z_min", s.band_z_min);
    v("band_z_max", s.band_z_max);
    v("row_margin", s.row_margin);
    v("lane_width_from_tracker", s.lane_width_from_tracker);
    v("estimator", s.estimator);
  }
  void validate() const;
};

/// Label of a base-frame point from the rows detected in the same frame (the geometric
/// default above): `crop` within a row's half width + margin of its centre line, else `ground`.
map::PointLabel geometric_label(const Eigen::Vector2f& p_base, const core::RowObservation& rows,
                                double row_margin);

/// A key location validated by the map stage (the key of a validated transition, Emmi 2021
/// sec. "Guidance control and map update"), in the odometry frame.
struct PlaceKey {
  map::Place from = map::Place::unknown;  ///< place left
  map::Place to = map::Place::unknown;    ///< place entered
  map::KeyLocation key;                   ///< p, v in the odom frame
  double stamp = 0.0;                     ///< [s] validation
};

/// The key location of the transition `estimate` validated (its map's newest), mapped from
/// F_f into the odom frame; nullopt when the frame validated none.
std::optional<PlaceKey> validated_key(const map::PlaceEstimator& estimator,
                                      const map::PlaceEstimate& estimate);

/// Builds the estimator's input of one frame. Keeps its buffers between frames; never throws.
class PlaceInput {
 public:
  explicit PlaceInput(const PlaceConfig& config = {});
  /// A 3D sweep in the base frame. `labels`: one per point of `cloud_base` (same order), or
  /// empty for the geometric default; a size mismatch also falls back to the default.
  void collect(const core::PointCloud& cloud_base, const preprocess::GroundEstimator& ground,
               std::span<const map::PointLabel> labels, const core::RowObservation& rows);
  /// 2D points in the base frame (a planar scan after preprocessing): geometric default.
  void collect(std::span<const Eigen::Vector2f> points_base, const core::RowObservation& rows);
  const std::vector<Eigen::Vector3f>& points() const { return points_; }
  const std::vector<map::PointLabel>& labels() const { return labels_; }
  /// The labels of the last frame came with the cloud (false: geometric default).
  bool given_labels() const { return given_; }

 private:
  PlaceConfig config_;
  std::vector<Eigen::Vector3f> points_;
  std::vector<map::PointLabel> labels_;
  bool given_ = false;
};

}  // namespace rownav::navigate
