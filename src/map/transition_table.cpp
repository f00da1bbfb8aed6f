/// @file transition_table.cpp Emmi 2021 Table 1.
#include "rownav/map/transition_table.hpp"

#include <cmath>

namespace rownav::map {

namespace {

bool in_row_places(Place p) { return p == Place::lane || p == Place::alley; }

TransitionDecision stay(Place p, std::string_view why) { return {false, p, why}; }

}  // namespace

void TransitionTableConfig::validate() const {
  core::check_non_negative(reach_distance, "reach_distance");
  core::check_non_negative(max_pass_offset, "max_pass_offset");
}

bool key_reached(const KeyLocation& k, const core::Pose2& T, const TransitionTableConfig& c) {
  const Eigen::Vector2d d = T.translation() - k.p;
  if (d.norm() <= c.reach_distance) return true;  // Table 1: "Reached: euc_dis <= 0.01 m"
  if (!c.passed_is_reached) return false;
  const double across = std::abs(k.v.x() * d.y() - k.v.y() * d.x());
  return d.dot(k.v) >= 0.0 && across <= c.max_pass_offset;
}

TransitionDecision evaluate_transition(Place last, Place estimate,
                                       const std::optional<KeyLocation>& entry,
                                       const std::optional<KeyLocation>& exit,
                                       const core::Pose2& T, const TransitionTableConfig& c) {
  if (estimate == last) return stay(last, "same place");
  if (estimate == Place::unknown || estimate == Place::gate) return stay(last, "estimate unclear");
  const bool from_open = last == Place::headland || last == Place::unknown;
  if (from_open && in_row_places(estimate)) {  // Table 1, rows "headland / unknown"
    if (entry && key_reached(*entry, T, c)) return {true, estimate, "entry key location reached"};
    return stay(last, "entry key location far");
  }
  if (in_row_places(last) && estimate == Place::headland) {  // Table 1, rows "lane / alley"
    if (exit && key_reached(*exit, T, c)) return {true, estimate, "exit key location reached"};
    return stay(last, "exit key location far");
  }
  if (last == Place::unknown && estimate == Place::headland)
    return {true, estimate, "relocated in the headland"};
  return stay(last, "transition not in the field model");
}

}  // namespace rownav::map
