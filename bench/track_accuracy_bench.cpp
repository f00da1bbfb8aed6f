// Open-loop tracking accuracy matrix: detectors x trackers (+ "none": the raw detector corridor)
// x the open-loop scenarios of tests/track/open_loop_harness.hpp. Prints markdown tables
// (lateral / heading RMSE and max, lost lane frames) for BENCHMARK.md. Not a Google Benchmark:
// one deterministic pass (fixed seeds).
#include <cstdio>
#include <string>
#include <vector>

#include "track/open_loop_harness.hpp"

int main() {
  using namespace rownav::test;
  const std::vector<std::string> detectors = {"hough_skew", "parallel_lines", "pearl",
                                              "ruby",       "ransac_lines",   "cluster_rows"};
  const std::vector<std::string> trackers = {"none", "model_matching", "line_ekf", "model_filter"};
  for (const auto& s : open_loop_scenarios()) {
    const OpenLoopRecording rec = simulate(s);
    std::printf("\n### %s (%zu sweeps)\n\n", s.name.c_str(), rec.clouds.size());
    std::printf(
        "| detector | tracker | lateral RMSE [mm] | lateral max [mm] | heading RMSE [deg] "
        "| heading max [deg] | lost / lane frames |\n|---|---|---|---|---|---|---|\n");
    for (const auto& d : detectors)
      for (const auto& t : trackers) {
        const OpenLoopScore sc = run_open_loop(rec, s, d, t);
        std::printf("| %s | %s | %.1f | %.1f | %.2f | %.2f | %d / %d |\n", d.c_str(), t.c_str(),
                    1000 * sc.lat_rmse, 1000 * sc.lat_max, sc.head_rmse_deg, sc.head_max_deg,
                    sc.lost_in_lane, sc.lane_frames);
        std::fflush(stdout);
      }
  }
  return 0;
}
