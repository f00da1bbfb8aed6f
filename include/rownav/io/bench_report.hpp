#pragma once
/// @file bench_report.hpp Writes the benchmark tables: OUT/tables.md (markdown, n/a for missing
/// values), OUT/tables.json ({"scenario", "tables": [{key, title, columns, rows: [[...]]}]}, null
/// for missing values) and one SVG bar plot per table that has a plot column
/// (OUT/plots/<key>.svg).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rownav/io/bench_tables.hpp"

namespace rownav::io {

/// Text of a table value: "n/a" for nullopt, else up to 3 decimals (integers without).
std::string format_value(const std::optional<double>& v);

/// The markdown document of the tables.
std::string tables_markdown(const std::string& scenario, const std::vector<ResultTable>& tables);

/// Writes tables.md, tables.json and plots/*.svg into `out`; returns the written files.
std::vector<std::filesystem::path> write_tables(const std::filesystem::path& out,
                                                const std::string& scenario,
                                                const std::vector<ResultTable>& tables);

}  // namespace rownav::io
