// Detection accuracy of every registered detector: the standard simulated scenarios and the real
// corn data set. Not a Google Benchmark (own main): prints the markdown tables for BENCHMARK.md
// and writes the JSON given by --json.
//
//   build/detect_accuracy_bench [--quick] [--json out.json] [--detector NAME]...
//                               [--config-dir DIR] [--corn-stride N] [--no-sim] [--no-corn]
// Google Benchmark flags (--benchmark_*, as `make bench` passes) are ignored.
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "rownav/io/detection_eval.hpp"
#include "rownav/io/detector_registry.hpp"

namespace {

namespace fs = std::filesystem;
using namespace rownav;

struct Args {
  bool quick = false, sim = true, corn = true;
  std::string json;
  std::vector<std::string> detectors;
  fs::path config_dir = fs::path(ROWNAV_SOURCE_DIR) / "config" / "detect";
  fs::path corn_dir = fs::path(ROWNAV_SHARED_DATA) / "corn_rows_2d";
  int corn_stride = 1;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(s + ": missing value");
      return argv[++i];
    };
    if (s.rfind("--benchmark", 0) == 0) continue;  // `make bench` passes Google Benchmark flags
    if (s == "--quick")
      a.quick = true;
    else if (s == "--no-sim")
      a.sim = false;
    else if (s == "--no-corn")
      a.corn = false;
    else if (s == "--json")
      a.json = value();
    else if (s == "--detector")
      a.detectors.push_back(value());
    else if (s == "--config-dir")
      a.config_dir = value();
    else if (s == "--corn-dir")
      a.corn_dir = value();
    else if (s == "--corn-stride")
      a.corn_stride = std::stoi(value());
    else
      throw std::invalid_argument("unknown argument " + s);
  }
  if (a.detectors.empty()) a.detectors = io::detector_names();
  return a;
}

std::vector<io::ScenarioEval> run_simulated(const Args& a) {
  std::vector<io::ScenarioEval> out;
  for (const auto& s : io::standard_scenarios(a.quick)) {
    std::cerr << "simulating " << s.name << " (" << s.lidar_preset << ", " << s.frames
              << " frames)..." << std::flush;
    const io::SimulatedFrames frames = io::simulate_frames(s);
    std::cerr << " detecting:";
    for (const auto& d : a.detectors) {
      auto pipeline = io::make_pipeline(d, a.config_dir / (s.crop + ".yaml"), frames.T_base_lidar);
      out.push_back(io::evaluate_frames(pipeline, frames, s));
      std::cerr << " " << d << std::flush;
    }
    std::cerr << "\n";
  }
  return out;
}

std::vector<io::CornEval> run_corn(const Args& a) {
  std::vector<io::CornEval> out;
  for (const auto& d : a.detectors) {
    std::cerr << "corn set: " << d << "..." << std::flush;
    auto pipeline = io::make_pipeline(d, a.config_dir / "row_crop.yaml");
    out.push_back(io::evaluate_corn(pipeline, a.corn_dir, a.corn_stride));
    std::cerr << " done\n";
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args a = parse(argc, argv);
    const auto sim = a.sim ? run_simulated(a) : std::vector<io::ScenarioEval>{};
    const auto corn = a.corn ? run_corn(a) : std::vector<io::CornEval>{};
    if (!sim.empty())
      std::cout << "### Simulated frames" << (a.quick ? " (quick)" : "") << "\n\n"
                << io::scenario_table_markdown(sim) << "\n";
    if (!corn.empty())
      std::cout << "### Real corn rows (corn_rows_2d, 2D LiDAR, hand-labelled lines)\n\n"
                << io::corn_table_markdown(corn) << "\n";
    if (!a.json.empty()) io::write_eval_json(a.json, sim, corn);
  } catch (const std::exception& e) {
    std::cerr << "detect_accuracy_bench: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
