#pragma once
/// @file controller_registry.hpp Path controllers by name, built from a control config file.
///
/// A control config file (config/control/default.yaml) is a map with one optional section per
/// controller, named as the controller (its Config). Keys are strict (io::decode_config); an
/// absent section keeps the defaults. Every section is checked, every section name must be a
/// known controller.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "rownav/control/controller.hpp"

namespace rownav::io {

/// Names of the registered controllers: stanley, lookahead_pid, fir_pid, pure_pursuit.
std::vector<std::string> controller_names();

/// Builds controller `name` from its section of `config` (empty path: defaults). InputError
/// "--controller: unknown controller 'x' (known: ...)" on an unknown name, or
/// "file:line:col: key: reason" on a bad file or key.
std::unique_ptr<control::PathController> make_controller(const std::string& name,
                                                         const std::filesystem::path& config);

}  // namespace rownav::io
