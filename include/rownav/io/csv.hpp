#pragma once
/// @file csv.hpp Small strict CSV helpers: a line reader whose errors name file and line, and
/// number formatting that reads back bit-identically.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace rownav::io {

/// Shortest text that parses back to exactly `v` (std::to_chars); "inf", "-inf", "nan".
std::string format_double(double v);
/// Shortest text that parses back to exactly `v` as a float.
std::string format_float(float v);

/// Parses a whole cell as a double (accepts "inf", "-inf", "nan", leading '+'); false if not one.
bool parse_double(std::string_view s, double& out);
/// Parses a whole cell as a float (same rules).
bool parse_float(std::string_view s, float& out);
/// Parses a whole cell as a decimal integer; false if not one or out of range.
bool parse_int64(std::string_view s, std::int64_t& out);

/// Reads a comma-separated file line by line. Blank lines and lines starting with '#' are skipped;
/// cells are trimmed of spaces, tabs and '\r'. No quoting (rownav CSVs hold numbers and names).
/// Every error is an InputError "<file>:<line>: <reason>".
class CsvReader {
 public:
  /// Loads the file; InputError "cannot open" when missing or unreadable.
  explicit CsvReader(const std::filesystem::path& file);

  /// Advances to the next non-blank line; false at the end of the file.
  bool next();
  /// 1-based line number of the current line.
  std::size_t line() const { return line_; }
  /// Cells of the current line.
  const std::vector<std::string_view>& cells() const { return cells_; }
  std::size_t size() const { return cells_.size(); }
  std::string_view cell(std::size_t i) const { return cells_.at(i); }

  /// Cell i as a double / float / integer; InputError naming `column` otherwise.
  double number(std::size_t i, std::string_view column) const;
  float number_f(std::size_t i, std::string_view column) const;
  std::int64_t integer(std::size_t i, std::string_view column) const;
  /// InputError unless the current line has exactly n cells.
  void expect_size(std::size_t n) const;
  /// InputError unless the current line is exactly these column names (a header check).
  void expect_header(const std::vector<std::string_view>& names) const;

  /// Throws InputError "<file>:<line>: <reason>".
  [[noreturn]] void fail(const std::string& reason) const;
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::string text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
  std::vector<std::string_view> cells_;
};

/// Quotes a value for an error message: at most 40 characters, control characters escaped.
std::string quote_for_message(std::string_view s);

}  // namespace rownav::io
