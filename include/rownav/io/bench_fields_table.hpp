#pragma once
/// @file bench_fields_table.hpp The `fields` tables of `rownav bench` (issue 10: "a table per
/// crop kind and spacing band, with the failures listed"): runs feeding BenchTable::fields are
/// grouped by zoo band (fields named zoo_<seed>_<index>_<band>) or else by field name.
/// - `fields`: a row per group: runs, success [%], corridors served / planned [%], row spacing
///   min / max of the group's zoo fields (n/a for files), in-row mean displacement (mean over
///   runs) and max (max over runs), plants crushed (sum), collisions (runs), row-end error mean
///   (mean over runs) and max (max over runs);
/// - `fields_failures`: a row per run that did not succeed: field, stop reason (`no summary`
///   when the run left none), corridors served, planned, wrong entries, plants crushed,
///   simulated time.
#include <vector>

#include "rownav/io/bench_tables.hpp"

namespace rownav::io {

/// Appends the two tables when any run feeds BenchTable::fields.
void add_fields_tables(const std::vector<CellResult>& runs, std::vector<ResultTable>& out);

}  // namespace rownav::io
