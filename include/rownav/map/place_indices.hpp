#pragma once
/// @file place_indices.hpp Instantaneous place indices: P_index, A_index, cluster_idx and
/// c_index per place, the observation they make and the instantaneous state (Emmi 2021,
/// 002_806e72d300173f73.txt, sec. "Current state estimation", eq. (4)-(9), Fig. 4).
///
/// Eq. (6) is ambiguous in the paper's typesetting; rownav reads it as: lane and alley are
/// told apart by lane_idx / alley_idx (rows beside the robot on both sides / on one side), both
/// are weighted by the alignment with the rows (A_index) and by 1 - cluster_idx (eq. 7), and the
/// headland takes the rest: c_headland = 1 - max(c_lane, c_alley), so the indices sum to 1.
#include <array>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/map/key_location.hpp"
#include "rownav/map/labelled_clusters.hpp"
#include "rownav/map/place.hpp"

namespace rownav::map {

/// Configuration of the instantaneous indices.
struct PlaceIndicesConfig {
  /// [m] L: FR / BR are projected this far forward / backward of the robot (Emmi 2021 eq. (7),
  /// Fig. 4; user-defined in the paper)
  double projection_distance = 1.0;
  /// [m] a row is beside the robot when its extent reaches this far past the robot's abscissa
  /// (rownav: lane_idx / alley_idx of eq. (6))
  double beside_margin = 0.2;
  /// [-] top two c_index closer than this: the state is unknown (Emmi 2021 eq. (9): "minimum
  /// difference of approximately 0.05")
  double min_margin = 0.05;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("projection_distance", s.projection_distance);
    v("beside_margin", s.beside_margin);
    v("min_margin", s.min_margin);
  }
  void validate() const;
};

/// The indices of one frame.
struct PlaceIndices {
  double p_index_entry = 0.0;  ///< eq. (4): |Pearson correlation| of the valid entry positions
  double p_index_exit = 0.0;   ///< eq. (4) for the exits
  double a_index = 0.0;  ///< eq. (5): |cos| between the robot heading and the nearest row
  double cluster_idx = 1.0;  ///< eq. (7): misalignment with the nearest row, [0, 1]
  bool left_beside = false;   ///< a row beside the robot on its left
  bool right_beside = false;  ///< ... on its right
  /// c_index per filtered place (headland, lane, alley: filtered_index), sums to 1, eq. (6)
  std::array<double, kFilteredPlaces> c_index{1.0, 0.0, 0.0};
  Place instantaneous = Place::unknown;  ///< eq. (9): argmax, unknown within min_margin
  double margin = 0.0;  ///< top c_index minus the second
};

/// eq. (4): |Pearson correlation| of the x and y of positions: 0 for fewer than 3 positions,
/// 1 when one coordinate does not vary (the points lie on a line parallel to an axis).
double position_correlation(const std::vector<Eigen::Vector2d>& positions);

/// eq. (7): cluster_idx of the robot against one row, clamped to [0, 1].
double cluster_index(const RowCluster& row, const core::Pose2& T_local_base, double L);

/// Computes the indices of one frame from the rows in F_l, the robot pose in F_l, d, and the
/// valid key locations so far (for P_index). Never throws.
PlaceIndices compute_place_indices(const std::vector<RowCluster>& rows,
                                   const core::Pose2& T_local_base, double half_width,
                                   const std::vector<KeyLocation>& valid_keys,
                                   const KeyLocationConfig& key_config,
                                   const PlaceIndicesConfig& config);

/// eq. (9): argmax of c_index, unknown when the top two are closer than `min_margin`.
Place instantaneous_place(const std::array<double, kFilteredPlaces>& c, double min_margin,
                          double* margin = nullptr);

}  // namespace rownav::map
