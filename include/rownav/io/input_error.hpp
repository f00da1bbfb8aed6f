#pragma once
/// @file input_error.hpp The one error type for bad input files: one line naming file, position
/// and reason, e.g. `field.yaml:12:5: vineyard.row_spacing: must be in [0.3, 10] (got 0)`.
#include <stdexcept>
#include <string>

namespace rownav::io {

/// Bad input file. `what()` is a single line: "<file>[:<position>]: <reason>".
class InputError : public std::runtime_error {
 public:
  /// @param file the offending file as given by the user
  /// @param position "line:col", "line 12", "feature 3", ... (empty when not applicable)
  /// @param reason what is wrong, without a trailing period
  InputError(const std::string& file, const std::string& position, const std::string& reason)
      : std::runtime_error(file + (position.empty() ? "" : ":" + position) + ": " + reason),
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
