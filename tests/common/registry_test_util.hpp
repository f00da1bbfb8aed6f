#pragma once
// Helpers of the registry tests (detectors, trackers, controllers): a YAML file in the temp
// directory and the one-line message of the InputError a call throws.
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "rownav/io/input_error.hpp"

namespace rownav::test {

/// Writes `text` to <tmp>/rownav_<prefix>_<name>.yaml and returns the path.
inline std::filesystem::path write_temp_yaml(const std::string& prefix, const std::string& name,
                                             const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / ("rownav_" + prefix + "_" + name + ".yaml");
  std::ofstream(p) << text;
  return p;
}

/// The message of the io::InputError `f` throws ("" when it does not throw one).
inline std::string input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace rownav::test
