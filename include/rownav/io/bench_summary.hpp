#pragma once
/// @file bench_summary.hpp A run's summary.json (docs/summary_json.md) as plain maps: numbers
/// (ints and bools as 0 / 1), strings and per-corridor numbers. Null and absent keys are absent.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rownav::io {

/// One summary.json.
struct RunSummary {
  std::map<std::string, double> numbers;  ///< number, integer and bool keys
  std::map<std::string, std::string> strings;
  std::vector<std::map<std::string, double>> per_corridor;  ///< numeric keys of each corridor

  /// The number of `key`, nullopt when null or absent.
  std::optional<double> get(const std::string& key) const;
};

/// Reads a summary.json; InputError on unreadable or malformed JSON (or not an object).
RunSummary read_summary(const std::filesystem::path& file);

}  // namespace rownav::io
