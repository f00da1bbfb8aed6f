#pragma once
/// @file mission_plan.hpp Which corridors of a block the robot serves, in which order, and on
/// which side the first headland turn goes (Bertoglio 2023, 003_25dc0df51a1e5faf.txt sec. II-B:
/// "the user needs to set the direction of the first rotation, left or right").
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"

namespace rownav::navigate {

/// Side of a headland turn, seen from the robot leaving a corridor.
enum class TurnSide : std::uint8_t { left, right };

/// +1 for left (y+), -1 for right (REP 103).
inline int side_sign(TurnSide s) {
  return s == TurnSide::left ? 1 : -1;
}

/// A mission: corridors of one block, served one after the other. The robot starts at the
/// entrance of the first corridor of the order. Corridor k lies between rows k and k+1.
struct MissionPlan {
  TurnSide first_turn = TurnSide::left;  ///< side of the next corridor at the first turn (003)
  std::vector<int> corridors;  ///< order of corridor indices to serve; empty: all, sweep order
  std::vector<int> skip;       ///< corridors left out of the sweep order
  int stop_after = 0;          ///< [corridors] serve at most this many (0: all)
  int block = 0;               ///< block of the field
  int start_corridor = 0;      ///< first corridor of the sweep order (corridors empty)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("first_turn", s.first_turn);
    v("corridors", s.corridors);
    v("skip", s.skip);
    v("stop_after", s.stop_after);
    v("block", s.block);
    v("start_corridor", s.start_corridor);
  }
  void validate() const;
};

/// The corridors to serve, in order, for a block of `corridor_count` corridors (given by the
/// operator; the robot has no map): the explicit order, or the sweep start_corridor,
/// start_corridor+1, ... (skips removed), cut at stop_after. Throws std::invalid_argument
/// naming the field when a corridor does not exist or the order is empty.
std::vector<int> resolve_order(const MissionPlan& plan, int corridor_count);

/// One headland transition of a resolved order: how many corridors across and to which side.
struct CorridorChange {
  int from = 0, to = 0;
  int shift = 1;                   ///< |to - from| corridors across
  TurnSide side = TurnSide::left;  ///< seen from the robot leaving `from`
};

/// Side of each transition: the first goes to plan.first_turn; the robot's heading reverses in
/// every corridor, so a change towards the same index direction flips side each time.
std::vector<CorridorChange> corridor_changes(const std::vector<int>& order, TurnSide first_turn);

}  // namespace rownav::navigate

template <>
struct rownav::core::EnumNames<rownav::navigate::TurnSide> {
  using E = rownav::navigate::TurnSide;
  static constexpr std::array<std::pair<E, std::string_view>, 2> values{
      {{E::left, "left"}, {E::right, "right"}}};
};

namespace rownav::navigate {
/// A sweep order in which consecutive corridors are at least `min_shift` apart (robots whose
/// turn radius exceeds half the spacing skip rows): residue classes 0, m, 2m, ... then 1, 1+m,
/// ... Falls back to 0..count-1 when count < 2 * min_shift + 1.
std::vector<int> skip_order(int corridor_count, int min_shift);
}  // namespace rownav::navigate
