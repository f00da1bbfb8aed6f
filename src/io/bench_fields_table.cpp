// Success and accuracy per field group, and the failed runs (definitions in the header).
#include "rownav/io/bench_fields_table.hpp"

#include <algorithm>
#include <limits>

#include "rownav/sim/field_zoo.hpp"

namespace rownav::io {

namespace {

using Runs = std::vector<const RunSummary*>;
using Value = std::optional<double>;

struct Group {
  std::string label;
  Runs runs;
  double spacing_min = std::numeric_limits<double>::infinity();
  double spacing_max = 0.0;
};

// Zoo fields group by band (and carry their spacing); other fields by name.
std::string group_of(const BenchCell& c, double* spacing) {
  const auto ref = sim::parse_zoo_ref(c.field.string());
  if (!ref) return c.field_name();
  const sim::FieldConfig f = sim::zoo_field(ref->index, ref->seed);
  *spacing = sim::nominal_row_spacing(f);
  return "zoo " + std::string(sim::zoo_band_name(ref->index % sim::kZooBands));
}

double sum(const Runs& runs, const std::string& key) {
  double s = 0.0;
  for (const auto* r : runs) s += r->get(key).value_or(0.0);
  return s;
}

Value rate(const Runs& runs, const std::string& key) {
  if (runs.empty()) return std::nullopt;
  return 100.0 * sum(runs, key) / static_cast<double>(runs.size());
}

Value served_share(const Runs& runs) {
  const double planned = sum(runs, "corridors_planned");
  if (planned <= 0.0) return std::nullopt;
  return 100.0 * sum(runs, "corridors_served") / planned;
}

ResultRow group_row(const Group& g) {
  const bool zoo = g.spacing_max > 0.0;
  return {
      {g.label},
      {double(g.runs.size()), rate(g.runs, "success"), served_share(g.runs),
       zoo ? Value(g.spacing_min) : std::nullopt, zoo ? Value(g.spacing_max) : std::nullopt,
       aggregate(g.runs, "in_row_mean_displacement", Aggregate::mean),
       aggregate(g.runs, "in_row_max_displacement", Aggregate::max), sum(g.runs, "plants_crushed"),
       sum(g.runs, "collision"), aggregate(g.runs, "row_end_error_mean", Aggregate::mean),
       aggregate(g.runs, "row_end_error_max", Aggregate::max)}};
}

ResultRow failure_row(const CellResult& r) {
  if (!r.summary) return {{r.cell.id, "no summary"}, std::vector<Value>(5)};
  const RunSummary& s = *r.summary;
  const auto reason = s.strings.find("stop_reason");
  return {{r.cell.id, reason == s.strings.end() ? "?" : reason->second},
          {s.get("corridors_served"), s.get("corridors_planned"), s.get("wrong_entries"),
           s.get("plants_crushed"), s.get("sim_time")}};
}

}  // namespace

void add_fields_tables(const std::vector<CellResult>& runs, std::vector<ResultTable>& out) {
  std::vector<Group> groups;
  ResultTable failures{"fields_failures",
                       "Runs that did not succeed",
                       {"run", "stop reason"},
                       {"served", "planned", "wrong entries", "crushed", "sim time [s]"},
                       {},
                       -1};
  for (const auto& r : runs) {
    if (!r.cell.feeds(BenchTable::fields)) continue;
    if (!r.summary || r.summary->get("success").value_or(0.0) == 0.0)
      failures.rows.push_back(failure_row(r));
    if (!r.summary) continue;
    double spacing = 0.0;
    const std::string label = group_of(r.cell, &spacing);
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const Group& g) { return g.label == label; });
    if (it == groups.end()) it = groups.insert(groups.end(), Group{label, {}});
    it->runs.push_back(&*r.summary);
    if (spacing > 0.0)
      it->spacing_min = std::min(it->spacing_min, spacing),
      it->spacing_max = std::max(it->spacing_max, spacing);
  }
  if (groups.empty() && failures.rows.empty()) return;
  ResultTable t{"fields",
                "Fields: success and accuracy per zoo band / field",
                {"fields"},
                {"runs", "success [%]", "corridors served [%]", "spacing min [m]",
                 "spacing max [m]", "displacement mean [m]", "displacement max [m]",
                 "plants crushed", "collisions", "row-end error mean [m]", "row-end error max [m]"},
                {},
                1};
  for (const auto& g : groups) t.rows.push_back(group_row(g));
  out.push_back(std::move(t));
  out.push_back(std::move(failures));
}

}  // namespace rownav::io
