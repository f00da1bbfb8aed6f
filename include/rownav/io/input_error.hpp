#pragma once
/// @file input_error.hpp The one error type for bad input files: one line naming file, position
/// and reason, e.g. `field.yaml:12:5: vineyard.row_spacing: must be in [0.3, 10] (got 0)`.
#include <cstdio>
#include <stdexcept>
#include <string>

namespace rownav::io {

/// `s` with every control character written as an escape (`\n`, `\x1b`): text taken from a
/// file (a topic, a key, a header word) can never break the one-line message or drive a terminal.
inline std::string escape_control(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c != 0x7f) {
      out += ch;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  return out;
}

/// Bad input file. `what()` is a single line: "<file>[:<position>]: <reason>", control
/// characters escaped (escape_control) whatever the parts hold.
class InputError : public std::runtime_error {
 public:
  /// @param file the offending file as given by the user
  /// @param position "line:col", "line 12", "feature 3", ... (empty when not applicable)
  /// @param reason what is wrong, without a trailing period
  InputError(const std::string& file, const std::string& position, const std::string& reason)
      : std::runtime_error(
            escape_control(file + (position.empty() ? "" : ":" + position) + ": " + reason)),
        file_(file),
        position_(position),
        reason_(reason) {}

  const std::string& file() const { return file_; }
  const std::string& position() const { return position_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string file_, position_, reason_;
};

}  // namespace rownav::io
