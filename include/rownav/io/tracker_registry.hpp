#pragma once
/// @file tracker_registry.hpp Row trackers by name, built from a tracking config file.
///
/// A tracking config file (config/track/default.yaml) is a map with one optional section per
/// tracker, named as the tracker (its Config). Keys are strict (io::decode_config); an absent
/// section keeps the defaults. Every section is checked, every section name must be a known
/// tracker.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "rownav/track/row_tracker.hpp"

namespace rownav::io {

/// Names of the registered trackers, in registration order.
std::vector<std::string> tracker_names();

/// Builds tracker `name` from its section of `config` (empty path: every default). InputError
/// "--tracker: unknown tracker 'x' (known: a, b)" for an unknown name, or at the offending key.
std::unique_ptr<track::RowTracker> make_tracker(const std::string& name,
                                                const std::filesystem::path& config);

}  // namespace rownav::io
