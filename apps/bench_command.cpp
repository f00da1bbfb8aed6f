// `rownav bench`: runs a scenario matrix of closed-loop simulated runs (`rownav run` child
// processes), writes the paper tables and, with --quick or --baseline, gates on a baseline.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <thread>

#include "commands.hpp"
#include "rownav/io/bench_baseline.hpp"
#include "rownav/io/bench_report.hpp"
#include "rownav/io/bench_runner.hpp"
#include "rownav/io/bench_scenario.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::app {

namespace {

namespace fs = std::filesystem;

struct BenchArgs {
  fs::path scenario = "bench/scenarios/full.yaml";
  fs::path out = "out/bench";
  fs::path runner, baseline;
  int jobs = 0;
  bool quick = false, update_baseline = false, scenario_given = false;
};

// Compares with (or rewrites) the baseline; true when nothing regressed.
bool gate(const BenchArgs& a, const std::vector<io::CellResult>& results) {
  const auto now = io::gate_metrics(results);
  if (a.update_baseline) {
    io::Baseline b;
    if (fs::exists(a.baseline)) b = io::read_baseline(a.baseline);
    b.scenario = a.scenario.generic_string();
    io::write_baseline(a.baseline, io::updated_baseline(b, now));
    std::cout << "baseline updated: " << a.baseline.string() << "\n";
    return true;
  }
  const auto regressions = io::check_baseline(io::read_baseline(a.baseline), now);
  for (const auto& line : regressions) std::cout << "REGRESSION " << line << "\n";
  if (regressions.empty()) std::cout << "baseline " << a.baseline.string() << ": no regression\n";
  return regressions.empty();
}

int run_bench(BenchArgs a) {
  if (a.quick && !a.scenario_given) a.scenario = "bench/scenarios/quick.yaml";
  if (a.quick && a.baseline.empty()) a.baseline = "bench/quick_baseline.json";
  if (a.update_baseline && a.baseline.empty())
    throw std::invalid_argument("--update-baseline: needs --quick or --baseline FILE");
  if (!a.update_baseline && !a.baseline.empty()) io::read_baseline(a.baseline);  // fail early
  const io::BenchScenario scenario = io::load_scenario(a.scenario);
  const auto cells = io::expand_scenario(scenario);
  io::BenchRunnerOptions o;
  o.runner = a.runner.empty() ? fs::read_symlink("/proc/self/exe") : a.runner;
  o.jobs =
      a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::cerr << "bench " << scenario.name << ": " << cells.size() << " cell(s), " << o.jobs
            << " job(s), output " << a.out.string() << "\n";
  const auto run = io::run_cells(cells, a.out, o);
  std::vector<std::string> warnings;
  const auto results = io::collect_results(cells, a.out, &warnings);
  for (const auto& w : warnings) std::cerr << "bench: warning: " << w << "\n";
  const auto files = io::write_tables(a.out, scenario.name, io::build_tables(results));
  std::cout << "cells: " << cells.size() << " (ran " << run.count(io::CellStatus::ran)
            << ", resumed " << run.count(io::CellStatus::resumed) << ", failed "
            << run.count(io::CellStatus::failed) << ", not run "
            << run.count(io::CellStatus::not_run) << ")\n";
  for (const auto& c : run.cells)
    if (c.status == io::CellStatus::failed)
      std::cout << "failed cell " << c.id << ": " << c.detail << "\n";
  std::cout << "tables: " << files[0].string() << ", " << files[1].string() << "\n";
  if (run.interrupted) return 130;
  const bool passed = a.baseline.empty() || gate(a, results);
  return passed && run.count(io::CellStatus::failed) == 0 ? 0 : 1;
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto a = std::make_shared<BenchArgs>();
  CLI::App* c = app.add_subcommand(
      "bench",
      "Run a benchmark scenario (a matrix of closed-loop simulated runs, each a `rownav run` "
      "child process writing OUT/runs/<id>/summary.json) and write the paper tables to "
      "OUT/tables.md, OUT/tables.json and OUT/plots/*.svg. Resumable: cells whose summary.json "
      "exists are not run again. Exit 0: all cells ran and no metric regressed; 1: a cell failed "
      "or a metric regressed (one line each); 2: bad input; 130: interrupted.");
  CLI::Option* scenario =
      c->add_option("--scenario", a->scenario, "scenario file (default bench/scenarios/full.yaml)");
  c->add_option("--out", a->out, "output folder (default out/bench)");
  c->add_option("--jobs,-j", a->jobs, "runs at a time (default: hardware threads)")
      ->check(CLI::PositiveNumber);
  c->add_flag("--quick", a->quick,
              "bench/scenarios/quick.yaml (unless --scenario) and the regression gate against "
              "bench/quick_baseline.json (unless --baseline)");
  c->add_option("--runner", a->runner,
                "executable run as `RUNNER run <options>` for each cell (default: this rownav)")
      ->check(CLI::ExistingFile);
  c->add_option("--baseline", a->baseline, "baseline JSON to gate on (metrics and tolerances)");
  c->add_flag("--update-baseline", a->update_baseline,
              "rewrite the baseline's values from these results (tolerances kept)");
  c->callback([a, scenario] {
    a->scenario_given = scenario->count() > 0;
    const int code = run_bench(*a);
    if (code == 0) return;
    std::cout.flush();
    std::cerr.flush();
    std::exit(code);
  });
}

}  // namespace rownav::app
