// `rownav zoo`: lists or writes the seeded zoo of random fields (sim/field_zoo.hpp, issue 10).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/sim/field_zoo.hpp"

namespace rownav::app {
namespace {

struct ZooOptions {
  int count = 100;
  int first = 0;
  std::uint64_t seed = 1;
  std::string out;
  std::string config;
  bool overwrite = false;
};

/// Lists the fields; with --out writes each as <out>/<name>.yaml and prints the `fields:` list
/// a bench scenario matrix takes (paths relative to the folder the scenario's root names).
void run_zoo(const ZooOptions& o) {
  const sim::ZooConfig z = o.config.empty() ? sim::ZooConfig{} : io::load_config<sim::ZooConfig>(o.config);
  if (!o.out.empty()) std::filesystem::create_directories(o.out);
  for (int i = o.first; i < o.first + o.count; ++i) {
    const sim::FieldConfig c = sim::zoo_field(i, o.seed, z);
    if (o.out.empty()) {
      std::printf("%4d %-36s %-9s spacing %.2f m, slope %.1f / %.1f deg\n", i, c.name.c_str(),
                  std::string(core::enum_name(c.kind)).c_str(), sim::nominal_row_spacing(c),
                  c.terrain.slope_x_deg, c.terrain.slope_y_deg);
      continue;
    }
    const std::filesystem::path file = std::filesystem::path(o.out) / (c.name + ".yaml");
    if (std::filesystem::exists(file) && !o.overwrite)
      throw std::invalid_argument("zoo --out: " + file.string() + " exists (use --overwrite)");
    io::save_yaml(file, io::encode_config(c));
    std::cout << "  - " << file.string() << "\n";
  }
}

}  // namespace

void add_zoo_command(CLI::App& app) {
  auto o = std::make_shared<ZooOptions>();
  CLI::App* c = app.add_subcommand(
      "zoo", "List or write the seeded zoo of random row-structured fields (vineyards, orchards, "
             "row crops; field i is in band i % 5)");
  c->add_option("--count", o->count, "number of fields (default 100)")->check(CLI::Range(1, 100000));
  c->add_option("--first", o->first, "index of the first field (default 0)")->check(CLI::NonNegativeNumber);
  c->add_option("--seed", o->seed, "zoo seed (default 1)");
  c->add_option("--config", o->config, "sim::ZooConfig YAML (bands; default: built in)")->check(CLI::ExistingFile);
  c->add_option("--out", o->out, "write each field as <out>/<name>.yaml (FieldConfig) instead of listing");
  c->add_flag("--overwrite", o->overwrite, "replace existing field files");
  c->callback([o] { run_zoo(*o); });
}

}  // namespace rownav::app
