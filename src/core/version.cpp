#include "rownav/core/version.hpp"

namespace rownav::core {

const char* version() { return "0.1.0"; }

}  // namespace rownav::core
