#pragma once
/// @file drive_model.hpp Drive model of the wheel odometry (part of the localizer.hpp contract;
/// in its own header so that wheel_odometry.hpp and localizer.hpp can both use it).
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"

namespace rownav::localize {

/// Drive model used to turn wheel / track speeds into a body twist.
enum class DriveModel : std::uint8_t { differential, skid_steer, ackermann };

}  // namespace rownav::localize

template <>
struct rownav::core::EnumNames<rownav::localize::DriveModel> {
  using E = rownav::localize::DriveModel;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::differential, "differential"},
       {E::skid_steer, "skid_steer"},
       {E::ackermann, "ackermann"}}};
};
