// The map stage's place as a gate on the navigator's exit and entry (issue 12, Emmi 2021
// Table 1: a transition is trusted when the place estimate and the key locations agree).
#include "rownav/navigate/place_gate.hpp"

namespace rownav::navigate {

GateVerdict exit_verdict(const std::optional<map::Place>& place, double past_exit,
                         const PlaceGateConfig& config) {
  if (!config.enabled || !place || *place != map::Place::lane) return GateVerdict::pass;
  return past_exit < config.exit_wait ? GateVerdict::wait : GateVerdict::contradict;
}

GateVerdict entry_verdict(const std::optional<map::Place>& place, const PlaceGateConfig& config) {
  if (!config.enabled || !place) return GateVerdict::pass;
  switch (*place) {
    case map::Place::headland:
      return GateVerdict::wait;
    case map::Place::alley:
    case map::Place::gate:
      return GateVerdict::contradict;
    default:
      return GateVerdict::pass;  // lane, or unknown: no opinion
  }
}

}  // namespace rownav::navigate
