#pragma once
/// @file transition_model_data.hpp HMM motion transition model of the map stage (generated).
///
/// Made by bench/place_transitions_bench.cpp (2000000 random poses per field, seed 1,
/// fields B1 and V1 of bench/map_fields.hpp, step 0.10 m): counts from -> to (headland, lane, alley)
///   426381 1196 524
///   1197 1499786 13903
///   526 13864 634355
/// Forbidden transitions (Emmi 2021 Fig. 1b: lane <-> alley) zeroed, rows normalised.
#include <array>

namespace rownav::map {

/// [m] forward travel of one motion step.
inline constexpr double kMotionStepLength = 0.10;
/// P(to | from, motion), row-major (headland, lane, alley).
inline constexpr std::array<double, 9> kMotionTransitions{
    0.99598226, 0.00279373, 0.00122401,
    0.00079748, 0.99920252, 0.00000000,
    0.00082850, 0.00000000, 0.99917150};

}  // namespace rownav::map
