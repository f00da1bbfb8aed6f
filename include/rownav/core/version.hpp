#pragma once
/// @file version.hpp Library version.

namespace rownav::core {

/// Semantic version of rownav ("major.minor.patch").
const char* version();

}  // namespace rownav::core
