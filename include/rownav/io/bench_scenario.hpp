#pragma once
/// @file bench_scenario.hpp Benchmark scenario files (bench/scenarios/*.yaml): named matrices of
/// closed-loop simulated runs, each the cartesian product of its lists, and the paper tables they
/// feed. Loaded strictly (one-line InputError "file:line:col: key: reason").
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"

namespace rownav::io {

/// The tables `rownav bench` writes (BENCHMARK.md, "Benchmark suite").
enum class BenchTable : std::uint8_t {
  malavazi_004,   ///< 004 Tables 1-3: success, crushed plants, path-length ratio per weed level
  bertoglio_003,  ///< 003 Tables I-II: centre displacement, corridor width, row-end error
  nehme_000,      ///< 000 Tables 1-2: lateral RMSE per corridor, per field
  lan_001,        ///< 001 Tables 2-3: line slope / intercept, lateral / heading errors
  timing,         ///< per-frame latency and simulated-to-wall time ratio per pipeline
  fields,         ///< success and accuracy per field group (zoo band or field), failures listed
};

/// One cartesian product of run settings. Paths are relative to the scenario's root.
struct BenchMatrixSpec {
  std::string name;                           ///< label of the matrix (letters, digits, _ -)
  std::vector<std::string> field_files;       ///< key `fields`: sim::FieldConfig YAML files
  int zoo_count = 0;             ///< [-] zoo fields zoo_first .. + zoo_count - 1 added to `fields`
  int zoo_first = 0;             ///< [-] index of the first zoo field (sim/field_zoo.hpp)
  std::uint64_t zoo_seed = 1;    ///< zoo seed
  std::vector<std::string> zoo_bands;  ///< zoo bands kept (empty: all; sim::zoo_band_name)
  std::vector<std::string> robots;            ///< robot files (config/robots/*.yaml)
  std::vector<std::string> sensors;           ///< sensor files (config/sensors/*.yaml)
  std::vector<std::string> missions;          ///< mission files (config/missions/*.yaml)
  std::vector<std::string> detectors;         ///< detector names (`rownav run --detector`)
  std::vector<std::string> trackers;          ///< tracker names; `none`: raw detections
  std::vector<std::string> controllers;       ///< controller names
  std::vector<std::string> row_end_policies;  ///< `--row-end-policy` values; empty: not passed
  std::vector<std::uint64_t> seeds;           ///< simulation seeds (or give seed_count)
  int seed_count = 0;                         ///< [-] seeds 1..seed_count (instead of seeds)
  double time_limit = 300.0;                  ///< [s] simulated time limit of every run
  std::vector<std::string> extra_args;        ///< appended verbatim to every run's options
  std::string nav_config;     ///< `--nav-config` file of every run (empty: the crop's default)
  std::string detect_config;  ///< `--detect-config` file of every run (empty: the crop's)
  std::vector<BenchTable> tables;             ///< tables these runs feed

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("name", s.name);
    v("fields", s.field_files);
    v("zoo_count", s.zoo_count);
    v("zoo_first", s.zoo_first);
    v("zoo_seed", s.zoo_seed);
    v("zoo_bands", s.zoo_bands);
    v("robots", s.robots);
    v("sensors", s.sensors);
    v("missions", s.missions);
    v("detectors", s.detectors);
    v("trackers", s.trackers);
    v("controllers", s.controllers);
    v("row_end_policies", s.row_end_policies);
    v("seeds", s.seeds);
    v("seed_count", s.seed_count);
    v("time_limit", s.time_limit);
    v("extra_args", s.extra_args);
    v("nav_config", s.nav_config);
    v("detect_config", s.detect_config);
    v("tables", s.tables);
  }
  void validate() const;
  /// The seeds of a run: `seeds`, or 1..seed_count.
  std::vector<std::uint64_t> seed_list() const;
  /// `fields`, then the kept zoo fields as references "zoo:SEED:INDEX".
  std::vector<std::string> field_list() const;
};

/// A scenario file.
struct BenchScenario {
  std::string name;                       ///< scenario name (progress lines, tables title)
  std::string description;                ///< free text
  std::string root = "../..";             ///< folder the matrices' paths are relative to,
                                          ///< relative to the scenario file's folder
  std::vector<BenchMatrixSpec> matrices;  ///< at least one

  /// Resolved `root` (set by load_scenario; not a field).
  std::filesystem::path base_dir;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("name", s.name);
    v("description", s.description);
    v("root", s.root);
    v("matrices", s.matrices);
  }
  void validate() const;
};

/// Loads a scenario file strictly. With `check_files`, every field / robot / sensor / mission
/// file must exist (InputError at the list entry otherwise).
BenchScenario load_scenario(const std::filesystem::path& file, bool check_files = true);

}  // namespace rownav::io

template <>
struct rownav::core::EnumNames<rownav::io::BenchTable> {
  using E = rownav::io::BenchTable;
  static constexpr std::array<std::pair<E, std::string_view>, 6> values{
      {{E::malavazi_004, "malavazi_004"},
       {E::bertoglio_003, "bertoglio_003"},
       {E::nehme_000, "nehme_000"},
       {E::lan_001, "lan_001"},
       {E::timing, "timing"},
       {E::fields, "fields"}}};
};
