// Aggregation of summary.json files into the paper tables (definitions in the header).
#include "rownav/io/bench_tables.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <set>

#include "rownav/io/bench_fields_table.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav/io/paper_figures.hpp"

namespace rownav::io {

namespace {

namespace fs = std::filesystem;
using Runs = std::vector<const RunSummary*>;
using Value = std::optional<double>;

struct Group {
  std::vector<std::string> labels;
  Runs runs;
};

// Runs feeding table `t` that have a summary, grouped by key(cell), in order of first appearance.
std::vector<Group> group_by(const std::vector<CellResult>& all, BenchTable t,
                            const std::function<std::vector<std::string>(const BenchCell&)>& key) {
  std::vector<Group> out;
  for (const auto& r : all) {
    if (!r.summary || !r.cell.feeds(t)) continue;
    const auto labels = key(r.cell);
    auto it =
        std::find_if(out.begin(), out.end(), [&](const Group& g) { return g.labels == labels; });
    if (it == out.end()) it = out.insert(out.end(), Group{labels, {}});
    it->runs.push_back(&*r.summary);
  }
  return out;
}

// [%] of runs for which pred holds; runs without the keys pred needs count as not.
Value rate(const Runs& runs, const std::function<bool(const RunSummary&)>& pred) {
  if (runs.empty()) return std::nullopt;
  const auto n = std::count_if(runs.begin(), runs.end(), [&](const auto* r) { return pred(*r); });
  return 100.0 * static_cast<double>(n) / static_cast<double>(runs.size());
}

bool is_true(const RunSummary& s, const std::string& key) {
  return s.get(key).value_or(0) != 0;
}

std::vector<std::string> fields_in(const std::vector<Group>& groups) {
  std::vector<std::string> out;
  for (const auto& g : groups)
    if (std::find(out.begin(), out.end(), g.labels[0]) == out.end()) out.push_back(g.labels[0]);
  return out;
}

void add_malavazi(const std::vector<CellResult>& all, std::vector<ResultTable>& out) {
  const auto groups = group_by(all, BenchTable::malavazi_004, [](const BenchCell& c) {
    return std::vector<std::string>{
        c.field_name(), c.detector,
        c.tracker == "none" ? "unfiltered" : "filtered (" + c.tracker + ")"};
  });
  for (const auto& field : fields_in(groups)) {
    ResultTable t{"malavazi_004_" + field,
                  "004 Tables 1-3 (Malavazi 2018): " + field,
                  {"detector", "variant"},
                  {"runs", "success [%]", "success, no plant crushed [%]", "path-length ratio mean",
                   "path-length ratio max", "path-length ratio min", "paper success [%]",
                   "paper no crush [%]", "paper ratio mean"},
                  {},
                  1};
    for (const auto& g : groups) {
      if (g.labels[0] != field) continue;
      const auto level = weed_level_of(field);
      const auto paper =
          level ? malavazi_2018_figures(*level, g.labels[1], g.labels[2] != "unfiltered")
                : std::nullopt;
      const auto fig = [&](double MalavaziFigures::*m) -> std::optional<double> {
        if (!paper || !std::isfinite((*paper).*m)) return std::nullopt;
        return (*paper).*m;
      };
      t.rows.push_back({{g.labels[1], g.labels[2]},
                        {double(g.runs.size()),
                         rate(g.runs, [](const auto& s) { return is_true(s, "success"); }),
                         rate(g.runs,
                              [](const auto& s) {
                                return is_true(s, "success") && s.get("plants_crushed") == 0.0;
                              }),
                         aggregate(g.runs, "path_length_ratio_mean", Aggregate::mean),
                         aggregate(g.runs, "path_length_ratio_max", Aggregate::max),
                         aggregate(g.runs, "path_length_ratio_min", Aggregate::min),
                         fig(&MalavaziFigures::success), fig(&MalavaziFigures::success_no_crush),
                         fig(&MalavaziFigures::ratio_mean)}});
    }
    out.push_back(std::move(t));
  }
}

void add_bertoglio(const std::vector<CellResult>& all, std::vector<ResultTable>& out) {
  // The robot file tells the protocol's speeds apart (bench/scenarios/bertoglio.yaml's *_2ms).
  const auto by_pipeline = group_by(all, BenchTable::bertoglio_003, [](const BenchCell& c) {
    return std::vector<std::string>{c.field_name(), c.robot.stem().string(), c.pipeline()};
  });
  if (by_pipeline.empty()) return;
  ResultTable t1{"bertoglio_003_table1",
                 "003 Table I (Bertoglio 2023): centre displacement and corridor width",
                 {"field", "robot", "pipeline"},
                 {"runs", "success [%]", "top speed [m/s]", "displacement mean [m]",
                  "displacement max [m]", "width mean [m]", "width max [m]", "width min [m]"},
                 {},
                 1};
  for (const auto& g : by_pipeline)
    t1.rows.push_back(
        {g.labels,
         {double(g.runs.size()), rate(g.runs, [](const auto& s) { return is_true(s, "success"); }),
          aggregate(g.runs, "speed_max", Aggregate::max),
          aggregate(g.runs, "in_row_mean_displacement", Aggregate::mean),
          aggregate(g.runs, "in_row_max_displacement", Aggregate::max),
          aggregate(g.runs, "corridor_width_mean", Aggregate::mean),
          aggregate(g.runs, "corridor_width_max", Aggregate::max),
          aggregate(g.runs, "corridor_width_min", Aggregate::min)}});
  out.push_back(std::move(t1));
  const auto by_policy = group_by(all, BenchTable::bertoglio_003, [](const BenchCell& c) {
    return std::vector<std::string>{c.field_name(), c.robot.stem().string(),
                                    c.row_end_policy.empty() ? "default" : c.row_end_policy};
  });
  // 003 Table II: every turn frame's end points against the pole centres (its measure), beside
  // the paper's simulation column and the row ends rownav's end of row estimated in the rows.
  ResultTable t2{"bertoglio_003_table2",
                 "003 Table II (Bertoglio 2023): row-end point error per policy",
                 {"field", "robot", "row-end policy"},
                 {"runs", "turn end points", "not row ends", "pole error mean [m]",
                  "pole error max [m]", "pole error min [m]", "paper mean [m]", "paper max [m]",
                  "paper min [m]", "estimated row end error mean [m]"},
                 {},
                 3};
  for (const auto& g : by_policy) {
    const auto paper = bertoglio_2023_pole_figures(g.labels[2]);
    const auto fig = [&](double BertoglioPoleFigures::*m) -> Value {
      return paper ? Value((*paper).*m) : std::nullopt;
    };
    t2.rows.push_back(
        {g.labels,
         {double(g.runs.size()), aggregate(g.runs, "turn_row_end_points", Aggregate::sum),
          aggregate(g.runs, "turn_row_end_spurious", Aggregate::sum),
          aggregate(g.runs, "turn_row_end_error_mean", Aggregate::mean),
          aggregate(g.runs, "turn_row_end_error_max", Aggregate::max),
          aggregate(g.runs, "turn_row_end_error_min", Aggregate::min),
          fig(&BertoglioPoleFigures::mean), fig(&BertoglioPoleFigures::max),
          fig(&BertoglioPoleFigures::min),
          aggregate(g.runs, "row_end_error_mean", Aggregate::mean)}});
  }
  out.push_back(std::move(t2));
}

// Mean lateral RMSE of corridor `corridor` over the runs (per_corridor entries).
Value corridor_rmse(const Runs& runs, double corridor) {
  double sum = 0;
  int n = 0;
  for (const auto* r : runs)
    for (std::size_t i = 0; i < r->per_corridor.size(); ++i) {
      const auto& c = r->per_corridor[i];
      const auto id = c.find("corridor");
      const auto v = c.find("lateral_rmse");
      if (v == c.end() || (id != c.end() ? id->second : double(i)) != corridor) continue;
      sum += v->second;
      ++n;
    }
  return n ? Value(sum / n) : std::nullopt;
}

void add_nehme(const std::vector<CellResult>& all, std::vector<ResultTable>& out) {
  const auto groups = group_by(all, BenchTable::nehme_000, [](const BenchCell& c) {
    return std::vector<std::string>{c.field_name(), c.pipeline()};
  });
  for (const auto& field : fields_in(groups)) {
    ResultTable t{"nehme_000_" + field,
                  "000 Tables 1-2 (Nehme 2021): lateral RMSE [m] per corridor, " + field,
                  {"corridor"},
                  {},
                  {},
                  -1};
    std::vector<const Group*> cols;
    std::set<double> corridors;
    for (const auto& g : groups) {
      if (g.labels[0] != field) continue;
      cols.push_back(&g);
      t.value_columns.push_back(g.labels[1]);
      for (const auto* r : g.runs)
        for (std::size_t i = 0; i < r->per_corridor.size(); ++i) {
          const auto id = r->per_corridor[i].find("corridor");
          corridors.insert(id != r->per_corridor[i].end() ? id->second : double(i));
        }
    }
    for (const double c : corridors) {
      ResultRow row{{std::to_string(static_cast<long long>(c))}, {}};
      for (const auto* g : cols) row.values.push_back(corridor_rmse(g->runs, c));
      t.rows.push_back(std::move(row));
    }
    ResultRow all_rows{{"all rows"}, {}};
    for (const auto* g : cols)
      all_rows.values.push_back(aggregate(g->runs, "in_row_lateral_rmse", Aggregate::mean));
    t.rows.push_back(std::move(all_rows));
    out.push_back(std::move(t));
  }
}

void add_lan(const std::vector<CellResult>& all, std::vector<ResultTable>& out) {
  const auto groups = group_by(all, BenchTable::lan_001, [](const BenchCell& c) {
    return std::vector<std::string>{c.field_name(), c.pipeline()};
  });
  if (groups.empty()) return;
  ResultTable t{"lan_001",
                "001 Tables 2-3 (Lan 2021): line and tracking errors",
                {"field", "pipeline"},
                {"runs", "slope error mean", "slope error std", "intercept error mean [m]",
                 "intercept error std [m]", "lateral RMSE [m]", "lateral max [m]",
                 "heading RMSE [deg]", "heading max [deg]"},
                {},
                5};
  for (const auto& g : groups)
    t.rows.push_back(
        {g.labels,
         {double(g.runs.size()), aggregate(g.runs, "line_slope_error_mean", Aggregate::mean),
          aggregate(g.runs, "line_slope_error_std", Aggregate::mean),
          aggregate(g.runs, "line_intercept_error_mean", Aggregate::mean),
          aggregate(g.runs, "line_intercept_error_std", Aggregate::mean),
          aggregate(g.runs, "track_lateral_error_rmse", Aggregate::mean),
          aggregate(g.runs, "track_lateral_error_max", Aggregate::max),
          aggregate(g.runs, "track_heading_error_rmse_deg", Aggregate::mean),
          aggregate(g.runs, "track_heading_error_max_deg", Aggregate::max)}});
  out.push_back(std::move(t));
}

Value time_ratio(const Runs& runs) {
  double sim = 0, wall = 0;
  for (const auto* r : runs) {
    const auto s = r->get("sim_time"), w = r->get("wall_time");
    if (!s || !w) continue;
    sim += *s;
    wall += *w;
  }
  return wall > 0 ? Value(sim / wall) : std::nullopt;
}

void add_timing(const std::vector<CellResult>& all, std::vector<ResultTable>& out) {
  const auto groups = group_by(all, BenchTable::timing, [](const BenchCell& c) {
    return std::vector<std::string>{c.pipeline()};
  });
  if (groups.empty()) return;
  ResultTable t{
      "timing",     "Timing: per-frame latency and simulated / wall time",
      {"pipeline"}, {"runs", "latency median [ms]", "latency p99 [ms]", "sim / wall time"},
      {},           1};
  for (const auto& g : groups)
    t.rows.push_back(
        {g.labels,
         {double(g.runs.size()), aggregate(g.runs, "frame_latency_median_ms", Aggregate::median),
          aggregate(g.runs, "frame_latency_p99_ms", Aggregate::max), time_ratio(g.runs)}});
  out.push_back(std::move(t));
}

}  // namespace

std::optional<double> aggregate(const std::vector<const RunSummary*>& runs, const std::string& key,
                                Aggregate how) {
  std::vector<double> v;
  for (const auto* r : runs)
    if (const auto x = r->get(key)) v.push_back(*x);
  if (v.empty()) return std::nullopt;
  switch (how) {
    case Aggregate::mean:
      return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
    case Aggregate::max:
      return *std::max_element(v.begin(), v.end());
    case Aggregate::min:
      return *std::min_element(v.begin(), v.end());
    case Aggregate::median:
      std::sort(v.begin(), v.end());
      return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
    case Aggregate::sum:
      return std::accumulate(v.begin(), v.end(), 0.0);
  }
  return std::nullopt;
}

std::vector<CellResult> collect_results(const std::vector<BenchCell>& cells, const fs::path& out,
                                        std::vector<std::string>* warnings) {
  std::vector<CellResult> results;
  for (const auto& c : cells) {
    CellResult r{c, std::nullopt};
    const fs::path file = cell_dir(out, c) / "summary.json";
    if (fs::is_regular_file(file)) try {
        r.summary = read_summary(file);
      } catch (const InputError& e) {
        if (warnings) warnings->push_back(e.what());
      }
    results.push_back(std::move(r));
  }
  return results;
}

std::vector<ResultTable> build_tables(const std::vector<CellResult>& runs) {
  std::vector<ResultTable> out;
  add_malavazi(runs, out);
  add_bertoglio(runs, out);
  add_nehme(runs, out);
  add_lan(runs, out);
  add_timing(runs, out);
  add_fields_tables(runs, out);
  return out;
}

}  // namespace rownav::io
