// How a closed-loop run answered the simulator's faults (io/fault_metrics.hpp, issue 13).
#include "rownav/io/fault_metrics.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace rownav::io {

namespace {

using json = nlohmann::ordered_json;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kStill = 0.02;  // [m/s], [rad/s] true speed below which the robot stands

bool zero(const core::Twist2& t) { return t.v == 0.0 && t.omega == 0.0; }

/// The enabled faults' windows, by key.
std::vector<std::pair<std::string, const sim::FaultWindow*>> windows(const sim::FaultsConfig& c) {
  std::vector<std::pair<std::string, const sim::FaultWindow*>> out;
  auto add = [&](const char* name, const sim::FaultWindow& w) {
    if (w.enabled) out.emplace_back(name, &w);
  };
  add("lidar_dropout", c.lidar_dropout);
  add("lidar_rate", c.lidar_rate);
  add("cloud_nan", c.cloud_nan);
  add("point_loss", c.point_loss);
  add("frame_repeat", c.frame_repeat);
  add("lidar_time_backwards", c.lidar_time_backwards);
  add("lidar_stamp_stall", c.lidar_stamp_stall);
  add("odometry_slip", c.odometry_slip);
  add("encoder", c.encoder);
  add("gyro_bias", c.gyro_bias);
  add("gnss_jump", c.gnss_jump);
  add("person", c.person);
  return out;
}

/// First stamp >= t0 at which the command is zero: a watchdog or stop event (exact), else a
/// ground-truth sample's command (20 Hz).
std::optional<double> first_zero(const RunResult& run, double t0) {
  std::optional<double> best;
  for (const auto& e : run.events)
    if (e.stamp >= t0 && (e.kind == navigate::NavEventKind::input_stale ||
                          e.kind == navigate::NavEventKind::safe_stop)) {
      best = e.stamp;
      break;
    }
  for (const auto& s : run.samples)
    if (s.stamp >= t0 && zero(s.cmd)) {
      if (!best || s.stamp < *best) best = s.stamp;
      break;
    }
  return best;
}

FaultOutcome measure(const RunResult& run, const std::string& name, const sim::FaultWindow& w) {
  FaultOutcome f;
  f.fault = name;
  f.start = w.start, f.end = w.end();
  f.min_clearance = kInf;
  for (const auto& s : run.samples)
    if (s.stamp >= w.start) {
      f.state_at_start = std::string(core::enum_name(s.state));
      break;
    }
  const auto z = first_zero(run, w.start);
  // A zero long after the window is not this fault's answer (a turn's in-place stop, the end).
  if (z && *z <= w.end() + 1.0) f.zero_after = *z - w.start;
  if (!f.zero_after) return f;
  bool halted = false, zeroed = false;
  for (const auto& s : run.samples) {
    if (s.stamp < *z) continue;
    if (!halted && std::abs(s.twist.v) < kStill && std::abs(s.twist.omega) < kStill)
      halted = true, f.halted_after = s.stamp - w.start;
    zeroed = zeroed || zero(s.cmd);  // a sample holds the command of the step before it
    if (zeroed && !zero(s.cmd)) {
      f.resumed_after = s.stamp - w.end();
      break;
    }
  }
  return f;
}

std::string show(const std::optional<double>& v) {
  if (!v) return "-";
  std::ostringstream o;
  o << std::fixed << std::setprecision(2) << *v;
  return o.str();
}

json opt(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }
json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

}  // namespace

FaultReport fault_report(const RunResult& run, const sim::FaultsConfig& config) {
  FaultReport r;
  r.min_person_clearance = kInf;
  for (const auto& s : run.samples) {
    r.left_field = r.left_field || s.place == sim::Place::outside;
    r.min_person_clearance = std::min(r.min_person_clearance, s.obstacle_clearance);
  }
  for (const auto& [name, w] : windows(config)) {
    r.faults.push_back(measure(run, name, *w));
    if (name == "person") r.faults.back().min_clearance = r.min_person_clearance;
  }
  return r;
}

void write_fault_report(const std::filesystem::path& dir, const FaultReport& report,
                        const RunSummary& summary) {
  json j;
  j["success"] = summary.success;
  j["stop_reason"] = summary.stop_reason;
  j["plants_crushed"] = summary.plants_crushed;
  j["collision"] = summary.collision;
  j["left_field"] = report.left_field;
  j["min_person_clearance"] = finite_or_null(report.min_person_clearance);
  j["sim_time"] = summary.sim_time;
  j["faults"] = json::array();
  for (const auto& f : report.faults)
    j["faults"].push_back({{"fault", f.fault},
                           {"start", f.start},
                           {"end", f.end},
                           {"state_at_start", f.state_at_start},
                           {"zero_after", opt(f.zero_after)},
                           {"halted_after", opt(f.halted_after)},
                           {"resumed_after", opt(f.resumed_after)},
                           {"min_clearance", finite_or_null(f.min_clearance)}});
  std::ofstream out(dir / "faults.json");
  out << j.dump(2) << "\n";
  if (!out) throw std::runtime_error((dir / "faults.json").string() + ": cannot write");
}

std::string describe(const FaultReport& report) {
  std::ostringstream o;
  for (const auto& f : report.faults) {
    o << "fault " << f.fault << " [" << show(f.start) << ", " << show(f.end) << ") s in "
      << f.state_at_start << ": zero command after " << show(f.zero_after) << " s, halted after "
      << show(f.halted_after) << " s, moving again " << show(f.resumed_after)
      << " s after its end";
    if (std::isfinite(f.min_clearance)) o << ", nearest " << show(f.min_clearance) << " m";
    o << "\n";
  }
  o << "left the field: " << (report.left_field ? "YES" : "no") << "\n";
  return o.str();
}

}  // namespace rownav::io
