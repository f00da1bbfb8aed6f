#pragma once
// Private to rownav_io: reading a whole JSON file with one-line errors (nlohmann_json is a
// private dependency, so this header is not installed).
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "rownav/io/input_error.hpp"

namespace rownav::io::detail {

/// Parses `file`; InputError "file: cannot open" or "file:byte N: malformed JSON".
inline nlohmann::json read_json_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "", "cannot open");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(file.string(), "byte " + std::to_string(e.byte), "malformed JSON");
  }
}

}  // namespace rownav::io::detail
