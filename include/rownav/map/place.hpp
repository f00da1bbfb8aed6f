#pragma once
/// @file place.hpp Semantic places of a field and the transitions allowed between them
/// (Emmi 2021, 002_806e72d300173f73.txt, sec. "The field model", Fig. 1b).
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"

namespace rownav::map {

/// Working place of the robot (Emmi 2021 eq. (1)): the states of the topological map.
enum class Place : std::uint8_t { headland, lane, alley, gate, unknown };

/// Number of places the HMM filters over (headland, lane, alley: Emmi 2021 sec. "Current state
/// estimation" discards the gate and keeps unknown outside the filter).
inline constexpr int kFilteredPlaces = 3;

/// Index of a filtered place (headland 0, lane 1, alley 2); -1 for gate / unknown.
constexpr int filtered_index(Place p) {
  switch (p) {
    case Place::headland: return 0;
    case Place::lane: return 1;
    case Place::alley: return 2;
    default: return -1;
  }
}

/// Filtered place of an index 0..2 (see filtered_index); unknown otherwise.
constexpr Place filtered_place(int i) {
  constexpr std::array<Place, kFilteredPlaces> places{Place::headland, Place::lane, Place::alley};
  return i >= 0 && i < kFilteredPlaces ? places[static_cast<std::size_t>(i)] : Place::unknown;
}

/// True when the field model allows going from `from` to `to` in one transition (Fig. 1b):
/// staying, headland <-> lane / alley / gate, anything -> unknown (lost) and unknown -> anything
/// (relocated). Lane <-> alley and lane / alley <-> gate go through the headland.
bool transition_allowed(Place from, Place to);

}  // namespace rownav::map

template <>
struct rownav::core::EnumNames<rownav::map::Place> {
  using E = rownav::map::Place;
  static constexpr std::array<std::pair<E, std::string_view>, 5> values{
      {{E::headland, "headland"}, {E::lane, "lane"}, {E::alley, "alley"}, {E::gate, "gate"},
       {E::unknown, "unknown"}}};
};
