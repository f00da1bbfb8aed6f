#pragma once
/// @file place_estimator.hpp The per-frame map stage: labelled points and odometry in, the
/// place (Emmi 2021 eq. (1)), its probabilities, the key locations and the map out (Emmi 2021,
/// 002_806e72d300173f73.txt, Fig. 2a). Meant to be called by navigate::NavStack once per frame.
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string_view>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/map/key_location.hpp"
#include "rownav/map/labelled_clusters.hpp"
#include "rownav/map/place.hpp"
#include "rownav/map/place_hmm.hpp"
#include "rownav/map/place_indices.hpp"
#include "rownav/map/point_labeller.hpp"
#include "rownav/map/topological_map.hpp"
#include "rownav/map/transition_table.hpp"

namespace rownav::map {

/// Configuration of the whole map stage.
struct PlaceEstimatorConfig {
  /// place the robot starts in (Emmi 2021 sec. "Experiments": placed at a lane / alley entrance
  /// or in the headland); unknown: found from the first transitions
  Place initial_place = Place::headland;
  /// [key locations] valid key locations kept per local frame for P_index (eq. (4)); older ones
  /// are forgotten (rownav: bounded memory and cost)
  int key_history = 50;
  LabelledClustersConfig clusters;
  KeyLocationConfig key_locations;
  PlaceIndicesConfig indices;
  PlaceHmmConfig hmm;
  TransitionTableConfig transitions;
  TopologicalMapConfig map;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("initial_place", s.initial_place);
    v("key_history", s.key_history);
    v("clusters", s.clusters);
    v("key_locations", s.key_locations);
    v("indices", s.indices);
    v("hmm", s.hmm);
    v("transitions", s.transitions);
    v("map", s.map);
  }
  void validate() const;
};

/// Quality of one estimate.
enum class EstimateStatus : std::uint8_t {
  ok,             ///< rows seen, the filtered state is clear
  no_crop,        ///< no crop row in view: the state is carried by the filter alone
  uncertain,      ///< the filtered state is unknown (top two posteriors too close)
  invalid_input   ///< non-finite pose or mismatched labels: the frame was ignored
};

/// Output of one frame.
struct PlaceEstimate {
  double stamp = 0.0;          ///< [s]
  Place place = Place::unknown;  ///< validated place (Table 1): what navigation should use
  Place filtered = Place::unknown;       ///< HMM estimate, eq. (10)
  Place instantaneous = Place::unknown;  ///< eq. (9), this frame alone
  std::array<double, kFilteredPlaces> probabilities{};  ///< PE(m_k), (headland, lane, alley)
  std::array<double, kFilteredPlaces> c_index{};        ///< eq. (6) this frame
  std::optional<KeyLocation> entry;  ///< last valid entry key location, F_f
  std::optional<KeyLocation> exit;   ///< last valid exit key location, F_f
  bool transition = false;           ///< a transition was validated this frame
  std::string_view reason;           ///< Table 1 reason of this frame
  int rows = 0;                      ///< row clusters in view
  EstimateStatus status = EstimateStatus::ok;
  double confidence = 0.0;  ///< top posterior
};

/// The map stage. Stateful; update() never throws (the constructor validates the config).
class PlaceEstimator {
 public:
  explicit PlaceEstimator(const PlaceEstimatorConfig& config = {});
  /// One frame: points in the base frame (x forward, y left, z up) with one label each, the
  /// odometry pose, the stamp [s].
  PlaceEstimate update(const std::vector<Eigen::Vector3f>& points_base,
                       const std::vector<PointLabel>& labels, const core::Pose2& T_odom_base,
                       double stamp);
  /// Starts again: map, frames, filter (the next update defines F_f).
  void reset();
  /// The a priori lane width d starts from (KeyLocationConfig::lane_width), e.g. the row
  /// spacing a row tracker measured; false (ignored) unless finite and > 0. Never throws.
  bool set_lane_width(double lane_width);
  Place place() const { return place_; }
  const TopologicalMap& map() const { return map_; }
  const std::vector<RowCluster>& rows() const { return clusters_.rows(); }
  const PlaceEstimatorConfig& config() const { return config_; }

 private:
  void validate_transition(PlaceEstimate& out, const core::Pose2& T_odom_base,
                           const core::Pose2& T_local_base, double stamp);

  PlaceEstimatorConfig config_;
  LabelledClusters clusters_;
  KeyLocator keys_;
  PlaceHmm hmm_;
  TopologicalMap map_;
  std::vector<KeyLocation> valid_keys_;  // valid key locations of this local frame (P_index)
  Place place_ = Place::unknown;
  std::optional<core::Pose2> last_pose_;
};

}  // namespace rownav::map

template <>
struct rownav::core::EnumNames<rownav::map::EstimateStatus> {
  using E = rownav::map::EstimateStatus;
  static constexpr std::array<std::pair<E, std::string_view>, 4> values{
      {{E::ok, "ok"}, {E::no_crop, "no_crop"}, {E::uncertain, "uncertain"},
       {E::invalid_input, "invalid_input"}}};
};
