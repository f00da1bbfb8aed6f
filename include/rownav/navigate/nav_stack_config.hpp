#pragma once
/// @file nav_stack_config.hpp The navigation settings of one crop: the navigator (mission state
/// machine, headland turns) and the end-of-row detector, in one YAML file
/// (config/navigate/<crop>.yaml: `navigator:` and `end_of_row:` sections).
///
/// The end-of-row height band and look-ahead box depend on the canopy (Lan 2021,
/// 001_b5f4b55a1b95775a.txt eq. 24 gives 0.5-1.3 m, 3-5 m for vines); `rownav run` picks the
/// crop's file like the detection config (config/detect/<crop>.yaml).
#include "rownav/core/config_fields.hpp"
#include "rownav/navigate/end_of_row.hpp"
#include "rownav/navigate/navigator.hpp"

namespace rownav::navigate {

/// Navigator + end-of-row configuration of one crop. Every default is the member's own.
struct NavStackConfig {
  NavigatorConfig navigator;  ///< mission state machine and headland turns
  EndOfRowConfig end_of_row;  ///< when the rows end ahead

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("navigator", s.navigator);
    v("end_of_row", s.end_of_row);
  }
  void validate() const {
    core::validate_nested(navigator, "navigator");
    core::validate_nested(end_of_row, "end_of_row");
  }
};

}  // namespace rownav::navigate
