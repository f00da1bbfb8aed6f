// Strict loading and validation of benchmark scenario files.
#include "rownav/io/bench_scenario.hpp"

#include <algorithm>
#include <set>

#include "rownav/io/yaml_config.hpp"
#include "rownav/sim/field_zoo.hpp"

namespace rownav::io {

namespace {

namespace fs = std::filesystem;

bool is_slug(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
  });
}

void check_list(const std::vector<std::string>& v, std::string_view key, bool names) {
  core::check(!v.empty(), key, "must not be empty");
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string at = std::string(key) + "[" + std::to_string(i) + "]";
    core::check(!v[i].empty(), at, "must not be empty");
    if (names) core::check(is_slug(v[i]), at, "must be a name (letters, digits, _ -)");
    for (std::size_t j = 0; j < i; ++j) core::check(v[i] != v[j], at, "duplicate entry");
  }
}

// Every file named in the matrices' path lists exists under the scenario's base_dir.
void check_files_exist(const BenchScenario& s, const YAML::Node& root, const std::string& file) {
  for (std::size_t m = 0; m < s.matrices.size(); ++m) {
    const auto& spec = s.matrices[m];
    const std::pair<const char*, const std::vector<std::string>*> lists[] = {
        {"fields", &spec.field_files},
        {"robots", &spec.robots},
        {"sensors", &spec.sensors},
        {"missions", &spec.missions}};
    for (const auto& [key, list] : lists)
      for (std::size_t i = 0; i < list->size(); ++i) {
        const fs::path p = s.base_dir / (*list)[i];
        if (fs::is_regular_file(p)) continue;
        const std::string path =
            "matrices[" + std::to_string(m) + "]." + key + "[" + std::to_string(i) + "]";
        detail::yaml_fail(file, root["matrices"][m][key][i], path,
                          "no such file " + p.lexically_normal().string());
      }
  }
}

}  // namespace

void BenchMatrixSpec::validate() const {
  core::check(is_slug(name), "name", "must be a name (letters, digits, _ -)");
  if (zoo_count == 0 || !field_files.empty()) check_list(field_files, "fields", false);
  core::check_non_negative(zoo_count, "zoo_count");
  core::check_non_negative(zoo_first, "zoo_first");
  for (std::size_t i = 0; i < zoo_bands.size(); ++i) {
    bool known = false;
    for (int b = 0; b < sim::kZooBands; ++b) known = known || zoo_bands[i] == sim::zoo_band_name(b);
    core::check(known, "zoo_bands[" + std::to_string(i) + "]",
                "not a zoo band (vineyard_narrow, vineyard_wide, orchard_free, orchard_hedgerow, "
                "row_crop)");
  }
  core::check(zoo_count == 0 || !field_list().empty(), "zoo_bands", "keeps no zoo field");
  check_list(robots, "robots", false);
  check_list(sensors, "sensors", false);
  check_list(missions, "missions", false);
  check_list(detectors, "detectors", true);
  check_list(trackers, "trackers", true);
  check_list(controllers, "controllers", true);
  if (!row_end_policies.empty()) check_list(row_end_policies, "row_end_policies", true);
  core::check(seeds.empty() != (seed_count == 0), seeds.empty() ? "seed_count" : "seeds",
              "give either seeds (a list) or seed_count (> 0), not both");
  core::check_non_negative(seed_count, "seed_count");
  core::check(std::set<std::uint64_t>(seeds.begin(), seeds.end()).size() == seeds.size(), "seeds",
              "duplicate seed");
  core::check_positive(time_limit, "time_limit");
  core::check(!tables.empty(), "tables", "must not be empty");
}

std::vector<std::uint64_t> BenchMatrixSpec::seed_list() const {
  if (!seeds.empty()) return seeds;
  std::vector<std::uint64_t> out;
  for (int i = 1; i <= seed_count; ++i) out.push_back(static_cast<std::uint64_t>(i));
  return out;
}

std::vector<std::string> BenchMatrixSpec::field_list() const {
  std::vector<std::string> out = field_files;
  for (int i = zoo_first; i < zoo_first + zoo_count; ++i) {
    const auto band = sim::zoo_band_name(i % sim::kZooBands);
    if (zoo_bands.empty() || std::find(zoo_bands.begin(), zoo_bands.end(), band) != zoo_bands.end())
      out.push_back(sim::zoo_ref_text({zoo_seed, i}));
  }
  return out;
}

void BenchScenario::validate() const {
  core::check(is_slug(name), "name", "must be a name (letters, digits, _ -)");
  core::check(!matrices.empty(), "matrices", "must not be empty");
  for (std::size_t i = 0; i < matrices.size(); ++i) {
    const std::string at = "matrices[" + std::to_string(i) + "]";
    core::validate_nested(matrices[i], at);
    for (std::size_t j = 0; j < i; ++j)
      core::check(matrices[i].name != matrices[j].name, at + ".name", "duplicate matrix name");
  }
}

BenchScenario load_scenario(const fs::path& file, bool check_files) {
  const YAML::Node root = load_yaml_file(file);
  BenchScenario s;
  decode_config(root, s, file.string());
  s.base_dir = (file.parent_path() / s.root).lexically_normal();
  if (!s.base_dir.empty() && !s.base_dir.has_filename()) s.base_dir = s.base_dir.parent_path();
  if (s.base_dir.empty()) s.base_dir = ".";
  if (check_files) check_files_exist(s, root, file.string());
  return s;
}

}  // namespace rownav::io
