// Cartesian expansion of benchmark matrices into cells with stable ids.
#include "rownav/io/bench_matrix.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <utility>

#include "rownav/io/yaml_config.hpp"
#include "rownav/sim/field_zoo.hpp"

namespace rownav::io {

namespace {

namespace fs = std::filesystem;

// FNV-1a, 64 bit: stable across platforms and runs (std::hash is not).
std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 1469598103934665603ull;
  for (const unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

// A zoo reference stays as it is; a file resolves against the scenario's root.
fs::path resolve_field(const BenchScenario& s, const std::string& field) {
  return sim::parse_zoo_ref(field) ? fs::path(field) : s.base_dir / field;
}

// The settings as written in the scenario (relative paths), one per line: the id's hash input.
std::string settings_text(const std::vector<std::string>& paths, const BenchCell& c) {
  std::string s;
  for (const auto& p : paths) s += p + "\n";
  s += c.detector + "\n" + c.tracker + "\n" + c.controller + "\n" + c.row_end_policy + "\n";
  s += std::to_string(c.seed) + "\n" + detail::yaml_format_double(c.time_limit) + "\n";
  for (const auto& a : c.extra_args) s += a + "\n";
  return s;
}

// The matrix's config files join the id's settings only when given (older ids unchanged).
std::vector<std::string> with_configs(std::vector<std::string> paths, const BenchMatrixSpec& m) {
  if (!m.nav_config.empty()) paths.push_back("nav:" + m.nav_config);
  if (!m.detect_config.empty()) paths.push_back("detect:" + m.detect_config);
  return paths;
}

std::string make_id(const std::vector<std::string>& paths, const BenchCell& c) {
  std::string slug =
      sim::field_label(paths[0]) + "_" + c.detector + "_" + c.tracker + "_" + c.controller;
  if (!c.row_end_policy.empty()) slug += "_" + c.row_end_policy;
  slug += "_s" + std::to_string(c.seed);
  char hash[16];
  std::snprintf(hash, sizeof hash, "%08llx",
                static_cast<unsigned long long>(fnv1a(settings_text(paths, c)) >> 32));
  return slug + "-" + hash;
}

// Adds the cells of one matrix; `index` maps ids to positions in `out` (merging duplicates).
void expand_matrix(const BenchScenario& s, const BenchMatrixSpec& m, std::vector<BenchCell>& out,
                   std::map<std::string, std::size_t>& index) {
  const std::vector<std::string> policies =
      m.row_end_policies.empty() ? std::vector<std::string>{""} : m.row_end_policies;
  for (const auto& field : m.field_list())
    for (const auto& robot : m.robots)
      for (const auto& sensor : m.sensors)
        for (const auto& mission : m.missions)
          for (const auto& det : m.detectors)
            for (const auto& trk : m.trackers)
              for (const auto& ctl : m.controllers)
                for (const auto& pol : policies)
                  for (const auto seed : m.seed_list()) {
                    BenchCell c;
                    c.field = resolve_field(s, field);
                    c.robot = s.base_dir / robot;
                    c.sensor = s.base_dir / sensor;
                    c.mission = s.base_dir / mission;
                    c.detector = det;
                    c.tracker = trk;
                    c.controller = ctl;
                    c.row_end_policy = pol;
                    c.seed = seed;
                    c.time_limit = m.time_limit;
                    c.extra_args = m.extra_args;
                    std::vector<std::string> paths = {field, robot, sensor, mission};
                    c.id = make_id(with_configs(paths, m), c);
                    // Config files resolved like the others (after the id: settings as written).
                    for (const auto& [opt, file] :
                         {std::pair{"--nav-config", m.nav_config},
                          std::pair{"--detect-config", m.detect_config}})
                      if (!file.empty())
                        c.extra_args.insert(c.extra_args.end(),
                                            {opt, (s.base_dir / file).string()});
                    const auto [it, added] = index.emplace(c.id, out.size());
                    if (added) out.push_back(std::move(c));
                    BenchCell& cell = out[it->second];
                    if (std::find(cell.matrices.begin(), cell.matrices.end(), m.name) ==
                        cell.matrices.end())
                      cell.matrices.push_back(m.name);
                    for (const auto t : m.tables)
                      if (!cell.feeds(t)) cell.tables.push_back(t);
                  }
}

}  // namespace

std::string BenchCell::field_name() const {
  return sim::field_label(field);
}

std::string BenchCell::pipeline() const {
  return detector + "+" + tracker + "+" + controller;
}

bool BenchCell::feeds(BenchTable t) const {
  return std::find(tables.begin(), tables.end(), t) != tables.end();
}

std::vector<std::string> BenchCell::run_args(const fs::path& out_dir) const {
  std::vector<std::string> a = {"--field",      field.string(),
                                "--robot",      robot.string(),
                                "--sensor",     sensor.string(),
                                "--mission",    mission.string(),
                                "--tracker",    tracker,
                                "--controller", controller,
                                "--seed",       std::to_string(seed),
                                "--time-limit", detail::yaml_format_double(time_limit),
                                "--out",        out_dir.string(),
                                "--quiet"};
  // `default`: the crop's detector (the detection config's `detector:` key, as `rownav run`).
  if (detector != kCropDetector) a.insert(a.end(), {"--detector", detector});
  if (!row_end_policy.empty()) a.insert(a.end(), {"--row-end-policy", row_end_policy});
  a.insert(a.end(), extra_args.begin(), extra_args.end());
  return a;
}

std::vector<BenchCell> expand_scenario(const BenchScenario& scenario) {
  std::vector<BenchCell> out;
  std::map<std::string, std::size_t> index;
  for (const auto& m : scenario.matrices) expand_matrix(scenario, m, out, index);
  return out;
}

fs::path cell_dir(const fs::path& out, const BenchCell& cell) {
  return out / "runs" / cell.id;
}

}  // namespace rownav::io
