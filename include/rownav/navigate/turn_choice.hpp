#pragma once
/// @file turn_choice.hpp Which headland turn a robot drives into the next corridor: in place
/// (Bertoglio 2023, 003_25dc0df51a1e5faf.txt sec. II-B), a U-turn of radius spacing / 2 (Lan
/// 2021, 001_b5f4b55a1b95775a.txt sec. 3.3) or a bulb (omega) turn when the robot's minimum
/// radius does not fit the lateral shift.
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"

namespace rownav::navigate {

/// Manoeuvre requested in the configuration.
enum class ManoeuvreChoice : std::uint8_t { automatic, in_place, u_turn, skip, three_point };
/// Manoeuvre actually driven.
enum class TurnKind : std::uint8_t { in_place, u_turn, bulb };

/// What a robot can do, for choosing a turn.
struct TurnAbility {
  bool can_turn_in_place = true;
  double min_turn_radius = 0.0;  ///< [m]
};

/// The chosen turn and its radius.
struct TurnPlan {
  TurnKind kind = TurnKind::in_place;
  double radius = 0.0;  ///< [m] arcs (u_turn, bulb)
  /// The robot can rotate in place; when not (car-like), it backs up along the pursuit arc when
  /// the look-ahead point falls behind it (a three-point correction) instead of rotating.
  bool can_rotate = true;
};

/// Turn for `shift` corridors across at `spacing` [m]: in_place for robots that can (automatic,
/// in_place); u_turn with radius r = max(spacing / 2, 1.25 r_min) when shift * spacing >= 2 r
/// (Lan 2021: radius = spacing / 2; the 25 % margin lets a car-like robot whose steering lags
/// come back onto the arc); otherwise a bulb of radius r. Never throws.
TurnPlan choose_turn(ManoeuvreChoice choice, int shift, double spacing, const TurnAbility& robot);

/// Smallest shift k (corridors) a U-turn of the robot can make at `spacing`:
/// k * spacing >= 2 * 1.25 r_min (choose_turn's radius margin; at least 1).
int min_feasible_shift(double spacing, double min_turn_radius);

}  // namespace rownav::navigate

template <>
struct rownav::core::EnumNames<rownav::navigate::ManoeuvreChoice> {
  using E = rownav::navigate::ManoeuvreChoice;
  static constexpr std::array<std::pair<E, std::string_view>, 5> values{
      {{E::automatic, "auto"},
       {E::in_place, "in_place"},
       {E::u_turn, "u_turn"},
       {E::skip, "skip"},
       {E::three_point, "three_point"}}};
};

template <>
struct rownav::core::EnumNames<rownav::navigate::TurnKind> {
  using E = rownav::navigate::TurnKind;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::in_place, "in_place"}, {E::u_turn, "u_turn"}, {E::bulb, "bulb"}}};
};
