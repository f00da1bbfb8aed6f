// Run report: summary.json, report.html (inline SVGs), top_view.svg / .png, lateral_error.png,
// speed.png, trajectory.csv, row_ends.csv (each estimated row end against the true one),
// row_end_points.csv (the turns' row-end points, when there were turns).
#include "rownav/io/run_report.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "rownav/io/cairo_canvas.hpp"
#include "rownav/io/plot.hpp"
#include "rownav/io/top_view.hpp"

namespace rownav::io {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json num(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? json(*v) : json();
}

Color state_colour(navigate::NavState s) {
  switch (s) {
    case navigate::NavState::in_row:
      return Color::hex("#1f77b4");
    case navigate::NavState::exiting:
      return Color::hex("#9467bd");
    case navigate::NavState::turning:
      return Color::hex("#ff7f0e");
    case navigate::NavState::headland:
      return Color::hex("#2ca02c");
    case navigate::NavState::entering:
      return Color::hex("#17becf");
    default:
      return Color::hex("#d62728");
  }
}

constexpr double kCrushRingMin = 0.15;  // [m] smallest ring drawn round a crushed plant

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error(file.string() + ": cannot write");
}

/// Field, ground-truth corridor centres, driven path coloured by state, estimated row ends.
void draw_top_view(Canvas& canvas, const RunResult& run, const sim::Field& field) {
  TopViewOptions o;
  o.pixels_per_metre = 12;
  o.title = "closed-loop run: true path coloured by navigator state";
  for (auto s :
       {navigate::NavState::in_row, navigate::NavState::exiting, navigate::NavState::turning,
        navigate::NavState::headland, navigate::NavState::entering})
    o.extra_legend.push_back({std::string(core::enum_name(s)), Style{state_colour(s), {}, 2.0}});
  o.extra_legend.push_back(
      {"row ends (estimated)", Style{Color::hex("#d62728"), Color::hex("#d62728"), 1.0, true}});
  if (!run.crushes.empty())
    o.extra_legend.push_back({"plant crushed", Style{Color::hex("#000000"), {}, 2.0}});
  const Color turn_ends = Color::hex("#17becf");  // the turns' row-end points (003 Table II)
  if (!run.turn_row_ends_world.empty())
    o.extra_legend.push_back({"row-end points in turns", Style{turn_ends, turn_ends, 1.0, true}});
  const Color key_colour = Color::hex("#9467bd");  // the map stage's key locations (issue 12)
  if (!run.key_locations.empty())
    o.extra_legend.push_back({"key locations (map)", Style{key_colour, key_colour, 1.0, true}});
  draw_field(canvas, field, o);
  std::vector<Eigen::Vector2d> seg;
  for (std::size_t i = 0; i < run.samples.size(); ++i) {
    seg.push_back(run.samples[i].T_world_base.translation());
    const bool last =
        i + 1 == run.samples.size() || run.samples[i + 1].state != run.samples[i].state;
    if (!last) continue;
    if (i + 1 < run.samples.size()) seg.push_back(run.samples[i + 1].T_world_base.translation());
    draw_path(canvas, seg, Style{state_colour(run.samples[i].state), {}, 2.0});
    seg.clear();
  }
  for (const auto& p : run.turn_row_ends_world) canvas.dot(p.world, 1.5, turn_ends);
  for (const auto& p : run.row_ends_world) canvas.dot(p, 4.0, Color::hex("#d62728"));
  for (const auto& c : run.crushes)  // a ring round each crushed plant, at least 0.15 m
    canvas.circle(c.position, std::max(c.radius, kCrushRingMin),
                  Style{Color::hex("#000000"), {}, 2.0});
  for (const auto& k : run.key_locations) canvas.dot(k.world, 3.0, key_colour);
}

/// Lateral error and speed over the driven distance; headland parts shaded.
void draw_plots(Canvas& lateral, Canvas& speed_canvas, const RunResult& run) {
  Series lat{"true lateral error [m]", {}, {}}, speed{"speed [m/s]", {}, {}},
      cmd{"commanded", {}, {}};
  cmd.color = Color::hex("#ff7f0e");
  cmd.dashed = true;
  PlotOptions po;
  double d = 0.0, band_start = -1.0;
  for (std::size_t i = 0; i < run.samples.size(); ++i) {
    const auto& s = run.samples[i];
    if (i > 0)
      d += (s.T_world_base.translation() - run.samples[i - 1].T_world_base.translation()).norm();
    const bool row = s.state == navigate::NavState::in_row && s.place == sim::Place::lane;
    lat.x.push_back(d), lat.y.push_back(row ? s.lateral_error : NAN);
    speed.x.push_back(d), speed.y.push_back(s.twist.v);
    cmd.x.push_back(d), cmd.y.push_back(s.cmd.v);
    if (!row && band_start < 0.0) band_start = d;
    if ((row || i + 1 == run.samples.size()) && band_start >= 0.0)
      po.bands.emplace_back(band_start, d), band_start = -1.0;
  }
  po.x_label = "distance [m]";
  po.band_label = "outside rows";
  po.title = "lateral error in rows (truth)";
  po.y_label = "m";
  draw_plot(lateral, {lat}, po);
  po.title = "speed";
  po.y_label = "m/s";
  draw_plot(speed_canvas, {speed, cmd}, po);
}

std::string html_escape(const std::string& s) {
  std::string o;
  for (char c : s)
    o += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return o;
}

std::string html(const RunResult& run, const json& summary, const std::string& top,
                 const std::pair<std::string, std::string>& pl) {
  std::ostringstream h;
  h << "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>rownav run</title><style>"
       "body{font-family:sans-serif;margin:20px}table{border-collapse:collapse}"
       "td,th{border:1px solid #ccc;padding:2px 8px;text-align:left}</style></head><body>"
    << "<h1>rownav closed-loop run: " << (summary["success"].get<bool>() ? "success" : "FAILED")
    << "</h1>\n<h2>Top view</h2>\n"
    << top << "\n<h2>Lateral error and speed</h2>\n"
    << pl.first << "\n"
    << pl.second << "\n<h2>Events</h2>\n<table><tr><th>t [s]</th><th>event"
    << "</th><th>corridor</th><th>what</th></tr>\n";
  for (const auto& e : run.events)
    h << "<tr><td>" << e.stamp << "</td><td>" << core::enum_name(e.kind) << "</td><td>"
      << e.corridor << "</td><td>" << html_escape(e.text) << "</td></tr>\n";
  h << "</table>\n<h2>Summary</h2>\n<table>\n";
  for (const auto& [k, v] : summary.items())
    if (k != "per_corridor") h << "<tr><td>" << k << "</td><td>" << v.dump() << "</td></tr>\n";
  h << "</table>\n<h2>Per corridor</h2>\n<table><tr><th>corridor</th><th>mean displacement [m]"
       "</th><th>max [m]</th><th>lateral RMSE [m]</th><th>heading RMSE [deg]</th><th>path "
       "length ratio</th></tr>\n";
  for (const auto& c : summary["per_corridor"])
    h << "<tr><td>" << c["corridor"] << "</td><td>" << c["mean_displacement"] << "</td><td>"
      << c["max_displacement"] << "</td><td>" << c["lateral_rmse"] << "</td><td>"
      << c["heading_rmse_deg"] << "</td><td>" << c["path_length_ratio"] << "</td></tr>\n";
  h << "</table></body></html>\n";
  return h.str();
}

std::string trajectory_csv(const RunResult& run) {
  std::ostringstream c;
  c.precision(9);
  // With the map stage on: the place it had validated by then (its last frame at or before the
  // sample) and the true one, so that a user can see where it lagged or erred (issue 12).
  const bool placed = !run.places.empty();
  // odom_*: the pose the stack believed, in its odom frame (origin and axes at the start pose),
  // so that the drift of its odometry can be read beside the truth.
  c << "stamp,x,y,theta,state,lateral_error,v,omega,corridor,odom_x,odom_y,odom_theta"
    << (placed ? ",place,true_place" : "") << "\n";
  auto place = run.places.begin();
  for (const auto& s : run.samples) {
    c << s.stamp << "," << s.T_world_base.x << "," << s.T_world_base.y << ","
      << s.T_world_base.theta << "," << core::enum_name(s.state) << ","
      << (s.place == sim::Place::lane ? s.lateral_error : NAN) << "," << s.twist.v << ","
      << s.twist.omega << "," << s.corridor << "," << s.T_odom_base.x << "," << s.T_odom_base.y
      << "," << s.T_odom_base.theta;
    if (placed) {
      while (std::next(place) != run.places.end() && std::next(place)->stamp <= s.stamp) ++place;
      c << "," << (place->stamp <= s.stamp ? core::enum_name(place->estimated) : "unknown") << ","
        << core::enum_name(s.place);
    }
    c << "\n";
  }
  return c.str();
}

/// Each row end the stack estimated against the nearest true one (world frame, metres).
std::string row_ends_csv(const RunSummary& s) {
  std::ostringstream c;
  c.precision(9);
  c << "x,y,true_x,true_y,error,along,across\n";
  for (const auto& e : s.row_ends)
    c << e.estimate.x() << "," << e.estimate.y() << "," << e.truth.x() << "," << e.truth.y() << ","
      << e.error << "," << e.along << "," << e.across << "\n";
  return c.str();
}

}  // namespace

std::string summary_json(const RunSummary& s, const RunNames& n) {
  json j;
  j["version"] = 1;
  j["field"] = n.field, j["robot"] = n.robot, j["sensor"] = n.sensor, j["mission"] = n.mission;
  j["detector"] = n.detector, j["tracker"] = n.tracker, j["controller"] = n.controller;
  j["seed"] = n.seed;
  j["success"] = s.success, j["mission_done"] = s.mission_done, j["safe_stop"] = s.safe_stop;
  j["stop_reason"] = s.stop_reason, j["collision"] = s.collision;
  j["corridors_planned"] = s.corridors_planned, j["corridors_served"] = s.corridors_served;
  j["corridors_in_order"] = s.corridors_in_order, j["turns"] = s.turns;
  j["correct_entries"] = s.correct_entries, j["wrong_entries"] = s.wrong_entries;
  j["plants_crushed"] = s.plants_crushed;
  j["in_row_mean_displacement"] = num(s.in_row_mean_displacement);
  j["in_row_max_displacement"] = num(s.in_row_max_displacement);
  j["in_row_lateral_rmse"] = num(s.in_row_lateral_rmse);
  j["in_row_heading_rmse_deg"] = num(s.in_row_heading_rmse_deg);
  j["path_length_ratio_mean"] = num(s.path_length_ratio_mean);
  j["path_length_ratio_max"] = num(s.path_length_ratio_max);
  j["path_length_ratio_min"] = num(s.path_length_ratio_min);
  j["corridor_width_mean"] = num(s.corridor_width_mean);
  j["corridor_width_max"] = num(s.corridor_width_max);
  j["corridor_width_min"] = num(s.corridor_width_min);
  j["row_end_error_mean"] = num(s.row_end_error_mean);
  j["row_end_error_max"] = num(s.row_end_error_max);
  j["row_end_along_mean"] = num(s.row_end_along_mean);
  j["turn_row_end_error_mean"] = num(s.turn_row_end_error_mean);
  j["turn_row_end_error_max"] = num(s.turn_row_end_error_max);
  j["turn_row_end_error_min"] = num(s.turn_row_end_error_min);
  j["turn_row_end_points"] = s.turn_row_end_points;
  j["turn_row_end_spurious"] = s.turn_row_end_spurious;
  j["frame_latency_median_ms"] = num(s.frame_latency_median_ms);
  j["frame_latency_p99_ms"] = num(s.frame_latency_p99_ms);
  j["track_lateral_error_rmse"] = num(s.track_lateral_error_rmse);
  j["track_lateral_error_max"] = num(s.track_lateral_error_max);
  j["track_heading_error_rmse_deg"] = num(s.track_heading_error_rmse_deg);
  j["track_heading_error_max_deg"] = num(s.track_heading_error_max_deg);
  j["line_slope_error_mean"] = num(s.line_slope_error_mean);
  j["line_slope_error_std"] = num(s.line_slope_error_std);
  j["line_intercept_error_mean"] = num(s.line_intercept_error_mean);
  j["line_intercept_error_std"] = num(s.line_intercept_error_std);
  j["tracking_lost_in_row"] = s.tracking_lost_in_row;
  j["sim_time"] = s.sim_time, j["wall_time"] = s.wall_time, j["distance"] = s.distance;
  j["speed_max"] = s.speed_max;
  j["odometry_alpha"] = s.odometry_alpha;
  j["odometry_scale_samples"] = s.odometry_scale_samples;
  j["crushed"] = json::array();
  for (const auto& c : s.crushes)
    j["crushed"].push_back({{"stamp", c.stamp},
                            {"x", c.position.x()},
                            {"y", c.position.y()},
                            {"radius", c.radius},
                            {"state", std::string(core::enum_name(c.state))},
                            {"robot_x", c.robot_xy.x()},
                            {"robot_y", c.robot_xy.y()}});
  j["per_corridor"] = json::array();
  for (const auto& c : s.per_corridor)
    j["per_corridor"].push_back({{"corridor", c.corridor},
                                 {"lateral_rmse", c.lateral_rmse},
                                 {"mean_displacement", c.mean_displacement},
                                 {"max_displacement", c.max_displacement},
                                 {"path_length_ratio", c.path_length_ratio},
                                 {"heading_rmse_deg", c.heading_rmse_deg}});
  j["place_frames"] = s.place.frames;
  j["place_accuracy"] = num(s.place.accuracy);
  j["key_location_error_median"] = num(s.place.key_error_median);
  j["key_location_error_max"] = num(s.place.key_error_max);
  j["key_locations"] = json::array();
  for (const auto& k : s.place.keys)
    j["key_locations"].push_back({{"from", k.from},
                                  {"to", k.to},
                                  {"x", k.world.x()},
                                  {"y", k.world.y()},
                                  {"error", k.error}});
  return j.dump(2);
}

void write_run_report(const fs::path& partial, const RunResult& run, const RunSummary& summary,
                      const RunNames& names, const sim::Field& field) {
  std::error_code ec;
  fs::create_directories(partial, ec);
  if (ec) throw std::runtime_error(partial.string() + ": cannot create: " + ec.message());
  const std::string js = summary_json(summary, names);
  write_text(partial / "summary.json", js + "\n");
  // One drawing a picture, written as SVG (inlined in report.html) and PNG (slides, READMEs).
  CairoCanvas top, lateral, speed;
  draw_top_view(top, run, field);
  draw_plots(lateral, speed, run);
  top.save(partial / "top_view.svg");
  write_text(partial / "report.html",
             html(run, json::parse(js), top.svg_inline("top-"),
                  {lateral.svg_inline("lateral-"), speed.svg_inline("speed-")}));
  top.save(partial / "top_view.png");
  lateral.save(partial / "lateral_error.png");
  speed.save(partial / "speed.png");
  write_text(partial / "trajectory.csv", trajectory_csv(run));
  if (!summary.row_ends.empty()) write_text(partial / "row_ends.csv", row_ends_csv(summary));
  if (!run.turn_row_ends_world.empty()) {  // 003 Table II's raw data: every turn frame's ends
    std::ostringstream c;
    c.precision(9);
    c << "stamp,x,y\n";
    for (const auto& p : run.turn_row_ends_world)
      c << p.stamp << "," << p.world.x() << "," << p.world.y() << "\n";
    write_text(partial / "row_end_points.csv", c.str());
  }
}

}  // namespace rownav::io
