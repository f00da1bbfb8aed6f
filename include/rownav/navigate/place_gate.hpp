#pragma once
/// @file place_gate.hpp The map stage's validated place (Emmi 2021, 002_806e72d300173f73.txt,
/// Table 1) as a second opinion on the two transitions the navigator decides by odometry and
/// the row tracker alone: leaving a lane at a row end, and entering the next lane (issue 12:
/// "the place estimate and the key locations gate the end-of-row and entry decisions; a
/// contradiction is a safe stop with its reason"). Small pure functions, as Nav2's regulated
/// pure pursuit heuristics.
#include <optional>

#include "rownav/core/config_fields.hpp"
#include "rownav/map/place.hpp"

namespace rownav::navigate {

/// The gate's settings (NavigatorConfig::place_gate). Used only when the map stage runs
/// (NavStack's PlaceConfig::enabled); without it the navigator decides as before.
struct PlaceGateConfig {
  /// gate the exit and the entry on the validated place. Off by default: on 32 seeded zoo fields
  /// the map stage is wrong for whole corridors in orchards (place accuracy 0.30-0.78) and the
  /// gate turned 7 successful missions into safe stops (BENCHMARK.md, issue 12)
  bool enabled = false;
  /// [m] past the exit point (row end + exit distance) the robot drives on along the row line
  /// waiting for the map's lane -> headland transition before a safe stop. The map validates it
  /// once the exit key location is behind the robot (Emmi 2021 sec. "Key locations"): measured
  /// 0.7-1.0 s (0.5-0.7 m at 0.7 m/s) after the true transition, 1.0 s before the exit point on
  /// demo_vineyard (BENCHMARK.md, issue 12)
  double exit_wait = 1.0;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("enabled", s.enabled);
    v("exit_wait", s.exit_wait);
  }
  void validate() const { core::check_non_negative(exit_wait, "exit_wait"); }
};

/// What a gate says of a transition the navigator is about to make.
enum class GateVerdict : std::uint8_t {
  pass,       ///< the map agrees, has no opinion (unknown) or is off
  wait,       ///< the map has not validated the transition yet: keep driving, ask again
  contradict  ///< the map places the robot where the plan says it cannot be: safe stop
};

/// The exit by odometry is done, `past_exit` [m] beyond its planned end: a map that still
/// validates `lane` says the rows go on (a gap read as a row end). Waits up to exit_wait, then
/// contradicts. `place`: nullopt when the map stage is off.
GateVerdict exit_verdict(const std::optional<map::Place>& place, double past_exit,
                         const PlaceGateConfig& config);

/// The entry check: the tracker sees the planned corridor. The map must agree that it is a lane:
/// headland waits (the entry key location is validated once behind the robot; the navigator's
/// entry_max_depth bounds the wait), an alley or a gate contradicts (a passage between two
/// fields, or the field's entrance, looks like a corridor to a row tracker that cannot tell the
/// crops apart: Emmi 2021's reason for labelled points).
GateVerdict entry_verdict(const std::optional<map::Place>& place, const PlaceGateConfig& config);

}  // namespace rownav::navigate
