#pragma once
// A fake `rownav run` for the bench tests: a shell script that parses the run options, appends
// "<detector> <seed>" to an invocation log, and writes a summary.json derived from the seed
// (success unless seed 3; in_row_mean_displacement 0.0<seed>; two corridors). Detector `broken`
// fails with exit 2 and no summary; detector `slow` sleeps 30 s first.
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace rownav::test {

inline std::filesystem::path write_fake_runner(const std::filesystem::path& dir) {
  const auto script = dir / "fake_rownav.sh";
  std::ofstream f(script);
  f << "#!/bin/sh\n"
       "[ \"$1\" = run ] || exit 2\nshift\n"
       "while [ $# -gt 0 ]; do case \"$1\" in\n"
       "  --quiet) shift;;\n"
       "  --detector) det=$2; shift 2;;\n  --tracker) trk=$2; shift 2;;\n"
       "  --field) field=$2; shift 2;;\n  --seed) seed=$2; shift 2;;\n"
       "  --out) out=$2; shift 2;;\n  *) shift 2;;\nesac; done\n"
       "echo \"$det $seed\" >> '"
    << (dir / "invocations.txt").string()
    << "'\n"
       "[ \"$det\" = slow ] && sleep 30\n"
       "if [ \"$det\" = broken ]; then echo \"unknown detector broken\" >&2; exit 2; fi\n"
       "ok=true; [ \"$seed\" = 3 ] && ok=false\n"
       "mkdir -p \"$out.partial\"\n"
       "cat > \"$out.partial/summary.json\" <<END\n"
       "{\"version\": 1, \"field\": \"f\", \"detector\": \"$det\", \"tracker\": \"$trk\", "
       "\"seed\": $seed, \"success\": $ok, \"plants_crushed\": 0, \"correct_entries\": 2, "
       "\"in_row_mean_displacement\": 0.0$seed, \"in_row_max_displacement\": 0.2$seed, "
       "\"row_end_error_mean\": null, \"frame_latency_median_ms\": 4.$seed, "
       "\"frame_latency_p99_ms\": 9, \"sim_time\": 60, \"wall_time\": 6, "
       "\"per_corridor\": [{\"corridor\": 0, \"lateral_rmse\": 0.1}, "
       "{\"corridor\": 1, \"lateral_rmse\": 0.$seed}]}\n"
       "END\n"
       "mkdir -p \"$out\" && mv \"$out.partial/summary.json\" \"$out/\" && rmdir \"$out.partial\"\n"
       "[ \"$ok\" = true ] || exit 1\n";
  f.close();
  std::filesystem::permissions(script, std::filesystem::perms::owner_all);
  return script;
}

/// A scenario file in `dir` with field / robot / sensor / mission files created there, one
/// matrix with the given detectors and seed list (YAML flow lists, e.g. "[a, b]").
inline std::filesystem::path write_test_scenario(const std::filesystem::path& dir,
                                                 const std::string& detectors,
                                                 const std::string& seeds,
                                                 const std::string& extra = "") {
  for (const char* f : {"f1.yaml", "robot.yaml", "sensor.yaml", "mission.yaml"})
    std::ofstream(dir / f) << "{}\n";
  const auto file = dir / "scenario.yaml";
  std::ofstream(file) << "name: test\nroot: .\nmatrices:\n"
                         "  - name: m\n"
                         "    fields: [f1.yaml]\n    robots: [robot.yaml]\n"
                         "    sensors: [sensor.yaml]\n    missions: [mission.yaml]\n"
                         "    detectors: "
                      << detectors << "\n    trackers: [model_filter]\n"
                      << "    controllers: [lookahead_pid]\n    seeds: " << seeds
                      << "\n    tables: [malavazi_004, nehme_000, timing]\n"
                      << extra;
  return file;
}

}  // namespace rownav::test
