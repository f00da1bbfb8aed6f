#pragma once
/// @file field_builder.hpp Builds any field from a FieldConfig, reading the layout and meshes
/// a `layout` field needs.
#include <filesystem>

#include "rownav/io/input_error.hpp"
#include "rownav/sim/field.hpp"
#include "rownav/sim/field_config.hpp"

namespace rownav::io {

/// Builds the field of `config`: procedural kinds through sim::generate_field; kind layout reads
/// config.layout.file (GeoJSON or CSV, rows ordered per block with sim::order_layout_rows), the
/// optional instance mesh (labelled canopy) and terrain mesh (labelled ground), then dresses the
/// rows with sim::dress_layout. Relative paths are resolved against `base_dir` (the directory of
/// the config file).
/// @throws std::invalid_argument for an invalid config (naming the field)
/// @throws InputError for a missing or malformed layout / mesh file
sim::Field build_field(const sim::FieldConfig& config, const std::filesystem::path& base_dir);

/// Builds the field of a field YAML (relative paths inside resolve against its folder), or of a
/// zoo reference "zoo:SEED:INDEX" (sim/field_zoo.hpp); `config_out`, when given, receives its
/// config. A missing layout / mesh file is an InputError at the field YAML key naming it.
sim::Field load_field(const std::filesystem::path& file, sim::FieldConfig* config_out = nullptr);

}  // namespace rownav::io
