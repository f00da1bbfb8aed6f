// Reading summary.json files into RunSummary.
#include "json_file.hpp"
#include "rownav/io/bench_summary.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

#include "rownav/io/input_error.hpp"

namespace rownav::io {

namespace {

using json = nlohmann::json;

void read_numbers(const json& j, std::map<std::string, double>& out) {
  for (const auto& [key, value] : j.items()) {
    if (value.is_boolean())
      out[key] = value.get<bool>() ? 1.0 : 0.0;
    else if (value.is_number())
      out[key] = value.get<double>();
  }
}

}  // namespace

std::optional<double> RunSummary::get(const std::string& key) const {
  const auto it = numbers.find(key);
  if (it == numbers.end()) return std::nullopt;
  return it->second;
}

RunSummary read_summary(const std::filesystem::path& file) {
  const json j = detail::read_json_file(file);
  if (!j.is_object()) throw InputError(file.string(), "", "expected a JSON object");
  RunSummary s;
  read_numbers(j, s.numbers);
  for (const auto& [key, value] : j.items())
    if (value.is_string()) s.strings[key] = value.get<std::string>();
  if (j.contains("per_corridor") && j["per_corridor"].is_array())
    for (const auto& c : j["per_corridor"]) {
      if (!c.is_object()) continue;
      read_numbers(c, s.per_corridor.emplace_back());
    }
  return s;
}

}  // namespace rownav::io
