#pragma once
/// @file layout_reader.hpp Reads row layouts (row polylines, optional plant / post positions)
/// from GeoJSON and CSV into a local metric frame.
///
/// Geographic coordinates (WGS84 longitude / latitude) become local east-north-up metres with
/// GeographicLib::LocalCartesian; the origin is the configured latitude / longitude or, when
/// those are NaN, the first coordinate of the first row kept.
///
/// **GeoJSON**: a FeatureCollection. A LineString (or each part of a MultiLineString) whose
/// `properties.type` is `row` or absent is a row; `properties.block` (string or number) names its
/// block. A Point whose `properties.kind` names a PlantKind (`vine`, `tree`, `crop`, `post`,
/// `end_post`) is a plant, assigned to the nearest row. Everything else (block outlines,
/// drainage lines, other points) is ignored. A plant Point may give its sizes in metres as the
/// number properties `trunk_diameter`, `trunk_height`, `crown_diameter`, `crown_height` (trees),
/// `height`, `width` (crop plants); sizes not given come from the field config. `type`, `block` and `kind` must be strings,
/// numbers or booleans (an array or object there is an error).
///
/// **CSV**: `#` comments and blank lines are skipped; the first other line is a header of
/// comma-separated column names, in any order: `row` (row label), either `x,y` (metres, local
/// frame) or `lon,lat` (degrees WGS84), optional `kind` (`row` (default) or a PlantKind: a plant
/// of row `row`), optional `block` (block name), optional plant sizes in metres (the GeoJSON
/// property names above; an empty cell takes the field config's size). Row points are taken in
/// file order.
/// @code
/// kind,block,row,lon,lat
/// row,A,1,-0.97747,51.59721
/// row,A,1,-0.97858,51.59670
/// post,A,1,-0.97800,51.59696
/// @endcode
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "rownav/io/input_error.hpp"
#include "rownav/sim/field.hpp"
#include "rownav/sim/field_config.hpp"

namespace rownav::io {

/// What to keep and where the local frame is.
struct LayoutReadOptions {
  std::vector<std::string> blocks;  ///< block names to keep (empty = all)
  double origin_lat_deg = std::numeric_limits<double>::quiet_NaN();  ///< [deg] NaN = first point
  double origin_lon_deg = std::numeric_limits<double>::quiet_NaN();  ///< [deg] NaN = first point
  sim::LayoutLimits limits;  ///< rows, plants, extent, total row length, JSON depth
};

/// Every reader enforces options.limits: at most max_rows rows and max_plants plants, rows
/// summing to at most max_total_row_length, every point (rows and plants kept) in a box of
/// max_extent (the error names the point farthest from the others), GeoJSON nested at most
/// max_json_depth deep; an InputError names the limit's key (`layout.limits.max_rows`, ...).

/// Reads a GeoJSON layout. Blocks are numbered in order of first appearance (of kept rows).
/// @throws InputError naming the feature index on malformed content, or when no row is left
sim::RowLayout read_geojson_layout(const std::filesystem::path& file,
                                   const LayoutReadOptions& options = {});

/// Reads a CSV layout (format above).
/// @throws InputError naming the line on malformed content, or when no row is left
sim::RowLayout read_csv_layout(const std::filesystem::path& file,
                               const LayoutReadOptions& options = {});

/// Reads a layout by extension: `.geojson` / `.json` or `.csv`.
/// @throws InputError for an unknown extension, a missing file or malformed content
sim::RowLayout read_layout(const std::filesystem::path& file,
                           const LayoutReadOptions& options = {});

}  // namespace rownav::io
