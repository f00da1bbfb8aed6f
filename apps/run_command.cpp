// `rownav run`: one closed-loop mission in the simulator, with a report.
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>

#include "commands.hpp"
#include "rownav/core/angle.hpp"
#include "rownav/io/closed_loop_runner.hpp"
#include "rownav/io/detector_registry.hpp"
#include "rownav/io/field_builder.hpp"
#include "rownav/io/controller_registry.hpp"
#include "rownav/io/fault_metrics.hpp"
#include "rownav/io/tracker_registry.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav/io/mission_io.hpp"
#include "rownav/io/progress.hpp"
#include "rownav/io/run_metrics.hpp"
#include "rownav/io/run_report.hpp"
#include "rownav/io/safe_output.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/navigate/nav_stack_config.hpp"
#include "rownav/sim/field_zoo.hpp"
#include "run_mission.hpp"
#include "setup.hpp"

namespace rownav::app {

namespace {

// Tracker and controller from their registries (config/track/default.yaml and
// config/control/default.yaml document every default); bad names / files fail here, before the
// simulation starts.
void make_stack(const RunArgs& a, io::ClosedLoopSetup& s) {
  const std::filesystem::path track_config = a.track_config.value_or("");
  const std::filesystem::path control_config = a.control_config.value_or("");
  io::make_tracker(a.tracker, track_config);
  io::make_controller(a.controller, control_config);
  s.make_tracker = [name = a.tracker, track_config] { return io::make_tracker(name, track_config); };
  s.make_controller = [name = a.controller, control_config] {
    return io::make_controller(name, control_config);
  };
}

// A crop's shipped config: `given` (--detect-config / --nav-config), else
// <config-dir>/<folder>/<kind>.yaml (as a user running from the repository expects), else every
// default (empty path).
std::filesystem::path crop_config_for(const RunArgs& a, const sim::FieldConfig& field,
                                      const std::optional<std::filesystem::path>& given,
                                      const char* folder, const char* option) {
  if (given) return *given;
  const sim::FieldKind kind =
      field.kind == sim::FieldKind::layout ? sim::FieldKind::vineyard : field.kind;
  const auto crop = a.config_dir / folder / (std::string(core::enum_name(kind)) + ".yaml");
  if (std::filesystem::exists(crop)) return crop;
  if (!a.quiet)
    std::cerr << "rownav run: no " << crop.string() << ": defaults (pass " << option << ")\n";
  return {};
}

// Navigator and end-of-row detector settings (navigate::NavStackConfig), strictly loaded.
void load_nav_stack(const RunArgs& a, const sim::FieldConfig& field, io::ClosedLoopSetup& s) {
  const auto file = crop_config_for(a, field, a.nav_config, "navigate", "--nav-config");
  if (file.empty()) return;
  s.nav = io::load_config<navigate::NavStackConfig>(file);
}

// A --faults file: only a `faults:` section (a mistyped top-level key is an error, not ignored).
struct FaultsFile {
  sim::FaultsConfig faults;
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("faults", s.faults);
  }
  void validate() const { core::validate_nested(faults, "faults"); }
};

void print_summary(const io::RunSummary& s, const RunArgs& a) {
  auto show = [](const std::optional<double>& v) {
    std::ostringstream o;
    if (v)
      o << std::fixed << std::setprecision(3) << *v;
    else
      o << "n/a";
    return o.str();
  };
  std::cout << (s.success ? "mission succeeded" : "mission FAILED") << " (" << s.stop_reason
            << "): " << s.corridors_served << "/" << s.corridors_planned << " corridors, "
            << s.correct_entries << "/" << s.turns << " correct entries, plants crushed "
            << s.plants_crushed << (s.collision ? ", COLLISION" : "") << "\n"
            << "in-row displacement mean " << show(s.in_row_mean_displacement) << " m, max "
            << show(s.in_row_max_displacement) << " m; path-length ratio "
            << show(s.path_length_ratio_mean) << "; row-end error " << show(s.row_end_error_mean)
            << " m\n"
            << "simulated " << std::fixed << std::setprecision(1) << s.sim_time << " s in "
            << s.wall_time << " s wall, " << s.distance << " m driven; frame latency median "
            << show(s.frame_latency_median_ms) << " ms\n";
  if (s.place.frames > 0)
    std::cout << "map stage: place accuracy " << show(s.place.accuracy) << " over "
              << s.place.frames << " frames; " << s.place.keys.size()
              << " key locations, error median " << show(s.place.key_error_median) << " m, max "
              << show(s.place.key_error_max) << " m\n";
  std::cout << "wrote " << (a.out / "summary.json").string() << " and "
            << (a.out / "report.html").string() << "\n";
}

}  // namespace

bool run_mission(const RunArgs& a) {
  // The output folder is checked first: a refused folder is said before minutes of simulation.
  io::OutputDir out(a.out, a.overwrite, "run");
  sim::FieldConfig field_config;
  const sim::Field field = io::load_field(a.field, &field_config);
  io::ClosedLoopSetup s;
  s.field = &field;
  s.robot = load_robot(a.robot);
  s.sensors = load_sensors(a.sensor, "");
  s.sensors.seed = a.seed;
  if (a.faults) s.sensors.faults = io::load_config<FaultsFile>(*a.faults).faults;
  s.mission = io::load_mission(a.mission);
  load_nav_stack(a, field_config, s);
  if (a.row_end_policy) s.nav.navigator.row_ends.policy = *a.row_end_policy;
  if (a.place) s.nav.place.enabled = true;
  s.truth_labels = a.labels == "truth";
  s.camera_labels = a.labels == "camera";
  // Every plant surface of the run's single field (vine canopy, tree crowns, crops) looks like
  // the target crop the default excess-green detector knows (class 0); there is no neighbour.
  s.camera.canopy_colour = s.camera.crown_colour = s.camera.crop_colour;
  s.labeller.false_positive_rate = a.label_fp;
  s.labeller.false_negative_rate = a.label_fn;
  s.labeller.validate();
  s.detect_config =
      crop_config_for(a, field_config, a.detect_config, "detect", "--detect-config");
  s.detector = a.detector.empty() ? io::default_detector(s.detect_config) : a.detector;
  s.time_limit = a.time_limit;
  if (a.lead_in) s.lead_in = *a.lead_in;
  s.start_offset = a.start_offset;
  s.start_yaw = core::deg2rad(a.start_yaw_deg);
  if (s.sensors.faults.any()) s.settle = 3.0;  // where the robot comes to rest after a stop
  make_stack(a, s);
  std::optional<io::Progress> bar;
  if (!a.quiet) {
    bar.emplace("mission", 100.0);
    s.progress = [&bar](double, double f) { bar->update(100.0 * f); };
  }
  const io::RunResult r = io::run_closed_loop(s);
  if (bar) bar->finish();
  const io::RunSummary summary = io::summarize(r, sim::FieldTruth(field), s.mission.block);
  io::RunNames names{sim::field_label(a.field),
                     a.robot.stem().string(),
                     a.sensor ? a.sensor->stem().string() : "default",
                     a.mission.stem().string(),
                     s.detector,
                     a.tracker,
                     a.controller,
                     a.seed};
  io::write_run_report(out.staging(), r, summary, names, field);
  std::optional<io::FaultReport> faults;
  if (s.sensors.faults.any()) {
    faults = io::fault_report(r, s.sensors.faults);
    io::write_fault_report(out.staging(), *faults, summary);
  }
  out.commit();
  print_summary(summary, a);
  for (const auto& e : r.events)  // what the robot could not avoid, said once per corridor
    if (e.kind == navigate::NavEventKind::narrow_corridor)
      std::cout << "warning: corridor " << e.corridor << ": " << e.text << "\n";
  // A safe stop says why in one line (the event's text: what the navigator saw).
  for (auto e = r.events.rbegin(); e != r.events.rend(); ++e)
    if (e->kind == navigate::NavEventKind::safe_stop) {
      std::cout << "stopped: " << e->text << "\n";
      break;
    }
  if (faults) std::cout << io::describe(*faults);
  return summary.success;
}

void add_run_command(CLI::App& app) {
  auto a = std::make_shared<RunArgs>();
  CLI::App* c = app.add_subcommand(
      "run",
      "Closed-loop mission in the simulator: the robot serves the planned corridors by "
      "itself (LiDAR rows, headland turns); writes summary.json and report.html");
  c->add_option("--field", a->field, "field YAML (config/fields), or zoo:SEED:INDEX (rownav zoo)")
      ->required()
      ->check(check_field_arg);
  c->add_option("--robot", a->robot, "robot YAML (config/robots)")
      ->required()
      ->check(CLI::ExistingFile);
  c->add_option("--mission", a->mission, "mission YAML (config/missions)")
      ->required()
      ->check(CLI::ExistingFile);
  c->add_option("--out", a->out, "output directory (new or empty; see --overwrite)")->required();
  c->add_flag("--overwrite", a->overwrite,
              "replace --out when it holds an earlier rownav output (never another folder)");
  c->add_option("--sensor", a->sensor, "sensors YAML (config/sensors); default OS1-16")
      ->check(CLI::ExistingFile);
  c->add_option("--detector", a->detector, "row detector (default: the detection config's `detector:` key, e.g. trunk_lines for orchards; else hough_skew)");
  c->add_option("--tracker", a->tracker, "row tracker: model_matching, line_ekf, model_filter (default), none (raw detector corridor)");
  c->add_option("--controller", a->controller, "path controller: stanley (default), lookahead_pid, fir_pid, pure_pursuit");
  c->add_option("--detect-config", a->detect_config, "detection config YAML")
      ->check(CLI::ExistingFile);
  c->add_option("--track-config", a->track_config, "tracker config YAML")->check(CLI::ExistingFile);
  c->add_option("--control-config", a->control_config, "controller config YAML")
      ->check(CLI::ExistingFile);
  c->add_option("--nav-config", a->nav_config,
                "navigation config YAML: navigator: and end_of_row: sections "
                "(navigate::NavStackConfig); default config/navigate/<crop>.yaml")
      ->check(CLI::ExistingFile);
  c->add_option("--config-dir", a->config_dir,
                "where config/detect/<crop>.yaml and config/navigate/<crop>.yaml are looked up "
                "when --detect-config / --nav-config are not given (default config)");
  c->add_option("--row-end-policy", a->row_end_policy,
                "each row end's point in the headland: nearest, line_fitting (Bertoglio 2023 "
                "sec. II-C) or end_slice (rownav; default: the nav config's row_ends.policy)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, navigate::RowEndPolicy>{
              {"nearest", navigate::RowEndPolicy::nearest},
              {"line_fitting", navigate::RowEndPolicy::line_fitting},
              {"end_slice", navigate::RowEndPolicy::end_slice}},
          CLI::ignore_case));
  c->add_option("--faults", a->faults,
                "faults YAML (config/faults): its `faults:` section (sim::FaultsConfig) replaces "
                "the sensors' one; writes faults.json")
      ->check(CLI::ExistingFile);
  c->add_flag("--place", a->place, "run the map stage (Emmi 2021 place, key locations; "
              "navigate config `place.enabled`)");
  c->add_option("--labels", a->labels,
                "map stage labels: truth (default), geometric or camera (a simulated camera, "
                "excess-green boxes, Emmi 2021 Fig. 2b)")
      ->check(CLI::IsMember({"truth", "geometric", "camera"}));
  c->add_option("--label-fp", a->label_fp, "truth labels' false-positive rate (default 0)");
  c->add_option("--label-fn", a->label_fn, "truth labels' false-negative rate (default 0)");
  c->add_option("--seed", a->seed, "simulation seed (default 1)");
  c->add_option("--time-limit", a->time_limit, "[s] simulated time limit (default 1800)");
  c->add_option("--lead-in", a->lead_in,
                 "[m] start this far before the first corridor's entrance (default 1.5; 0 = at "
                 "the row start, as an operator places a robot at the head of a bed)")
      ->check(CLI::Range(0.0, 100.0));
  c->add_option("--start-offset", a->start_offset,
                "[m] start this far left (+) or right (-) of the first corridor's centre line "
                "(default 0)")
      ->check(CLI::Range(-10.0, 10.0));
  c->add_option("--start-yaw", a->start_yaw_deg,
                "[deg] start heading from the corridor direction, counter-clockwise + (default 0)")
      ->check(CLI::Range(-90.0, 90.0));
  c->add_flag("--quiet", a->quiet, "no progress bar");
  c->callback([a] {
    if (!run_mission(*a)) {
      std::cout.flush();
      std::exit(1);  // the mission failed (safe stop, wrong corridor, timeout)
    }
  });
}

}  // namespace rownav::app
