#pragma once
/// @file transition_table.hpp Transition evaluation: the filtered state combined with the last
/// valid key locations (Emmi 2021, 002_806e72d300173f73.txt, sec. "Transition evaluation",
/// Table 1).
#include <optional>
#include <string_view>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/map/key_location.hpp"
#include "rownav/map/place.hpp"

namespace rownav::map {

/// Configuration of Table 1.
struct TransitionTableConfig {
  /// [m] a key location this close to the robot is reached (Emmi 2021 Table 1: 0.01 m)
  double reach_distance = 0.01;
  /// a key location the robot has passed (along its direction) is reached too (Emmi 2021: "A key
  /// location can also be considered reached if the point is passed by the robot")
  bool passed_is_reached = true;
  /// [m] ... when the robot passes it within this distance across its direction (rownav: a
  /// neighbouring lane's end is not passed)
  double max_pass_offset = 0.6;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("reach_distance", s.reach_distance);
    v("passed_is_reached", s.passed_is_reached);
    v("max_pass_offset", s.max_pass_offset);
  }
  void validate() const;
};

/// Outcome of Table 1 for one frame.
struct TransitionDecision {
  bool transition = false;   ///< the place changes to `next`
  Place next = Place::unknown;  ///< the validated place after this frame
  std::string_view reason;   ///< why (static text)
};

/// True when the robot (T_frame_base) has reached or passed key location `k` (same frame).
bool key_reached(const KeyLocation& k, const core::Pose2& T_frame_base,
                 const TransitionTableConfig& config);

/// Emmi 2021 Table 1: from the validated place `last` and the filtered estimate `estimate`,
/// with the last valid entry / exit key locations and the robot pose (all in one frame).
/// Headland / unknown -> lane / alley needs the entry reached; lane / alley -> headland needs
/// the exit reached; unknown -> headland is accepted (relocated); other changes are refused.
TransitionDecision evaluate_transition(Place last, Place estimate,
                                       const std::optional<KeyLocation>& entry,
                                       const std::optional<KeyLocation>& exit,
                                       const core::Pose2& T_frame_base,
                                       const TransitionTableConfig& config);

}  // namespace rownav::map
