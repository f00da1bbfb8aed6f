#pragma once
// TEMPORARY: until io::make_tracker / io::make_controller are merged, `rownav run` / `demo` use
// the test doubles (pass-through tracker, proportional controller). DELETE AT MERGE and wire the
// factories to make_tracker / make_controller (apps/run_command.cpp, make_stack()).
#include "../tests/common/nav_doubles.hpp"
