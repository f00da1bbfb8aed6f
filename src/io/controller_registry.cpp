#include "rownav/io/controller_registry.hpp"

#include <functional>
#include <string_view>

#include "rownav/control/fir_pid.hpp"
#include "rownav/control/lookahead_pid.hpp"
#include "rownav/control/pure_pursuit.hpp"
#include "rownav/control/stanley.hpp"
#include "rownav/io/section_registry.hpp"

namespace rownav::io {

namespace {

using Registry = SectionRegistry<control::PathController>;

// Registered controllers: adding one is one line here (and its section in default.yaml).
const Registry& registry() {
  static const Registry r("--controller", "controller",
                          {
                              {"stanley", Registry::creator<control::StanleyController>()},
                              {"lookahead_pid", Registry::creator<control::LookaheadPidController>()},
                              {"fir_pid", Registry::creator<control::FirPidController>()},
                              {"pure_pursuit", Registry::creator<control::PurePursuitController>()},
                          });
  return r;
}

}  // namespace

std::vector<std::string> controller_names() { return registry().names(); }

std::unique_ptr<control::PathController> make_controller(const std::string& name,
                                                         const std::filesystem::path& config) {
  return registry().make(name, config);
}

}  // namespace rownav::io
