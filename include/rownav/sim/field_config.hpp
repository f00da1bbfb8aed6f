#pragma once
/// @file field_config.hpp One config for any field: procedural vineyard / orchard / row crop, or
/// an imported layout dressed with vines. Imports need files: see io::build_field.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/sim/field.hpp"
#include "rownav/sim/orchard.hpp"
#include "rownav/sim/row_crop.hpp"
#include "rownav/sim/terrain.hpp"
#include "rownav/sim/vineyard.hpp"

namespace rownav::sim {

/// An imported row layout (GeoJSON / CSV) and optional meshes. Rows are dressed with
/// FieldConfig::vineyard (its rows, row_length, row_spacing and curvature fields are unused;
/// the row spacing is estimated from the layout).
struct LayoutConfig {
  std::string file;               ///< CSV or GeoJSON layout, relative to the config file
  std::string instance_mesh;      ///< optional vine-row mesh instanced along rows (replaces vines)
  double instance_spacing = 5.1;  ///< [m] distance between instances along a row
  std::string terrain_mesh;       ///< optional whole terrain / field mesh (world frame, labelled
                                  ///< ground), replaces the procedural ground
  std::vector<std::string> blocks;  ///< block names to keep (empty = all)
  double origin_lat_deg =
      std::numeric_limits<double>::quiet_NaN();  ///< [deg] ENU origin (NaN = first point)
  double origin_lon_deg =
      std::numeric_limits<double>::quiet_NaN();  ///< [deg] ENU origin (NaN = first point)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("file", s.file);
    v("instance_mesh", s.instance_mesh);
    v("instance_spacing", s.instance_spacing);
    v("terrain_mesh", s.terrain_mesh);
    v("blocks", s.blocks);
    v("origin_lat_deg", s.origin_lat_deg);
    v("origin_lon_deg", s.origin_lon_deg);
  }
  void validate() const;
};

/// Which field to build and how.
struct FieldConfig {
  FieldKind kind = FieldKind::vineyard;  ///< generator: vineyard, orchard, row_crop or layout
  std::string name = "vineyard";         ///< name given to the field
  VineyardConfig vineyard;               ///< kind vineyard, and vine dressing of kind layout
  OrchardConfig orchard;                 ///< kind orchard
  RowCropConfig row_crop;                ///< kind row_crop
  LayoutConfig layout;                   ///< kind layout
  TerrainConfig terrain;                 ///< ground shape (all kinds)
  std::uint64_t seed = 1;                ///< plant placement / shape seed

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("kind", s.kind);
    v("name", s.name);
    v("vineyard", s.vineyard);
    v("orchard", s.orchard);
    v("row_crop", s.row_crop);
    v("layout", s.layout);
    v("terrain", s.terrain);
    v("seed", s.seed);
  }
  /// Validates the sub-config of `kind` and the terrain.
  void validate() const;
};

/// Generates a procedural field (kind vineyard, orchard or row_crop).
/// @throws std::invalid_argument for kind layout (needs files: use io::build_field) or an
///         invalid config
Field generate_field(const FieldConfig& config);

/// Orders the rows of each block by lateral position: all rows of a block are oriented like its
/// longest row, and sorted along that row's left normal (so corridor k lies on the left of row
/// k). Blocks keep their order of first appearance.
void order_layout_rows(RowLayout& layout);

/// [m] median distance between adjacent rows of the same block (0 when no block has 2 rows).
double estimate_row_spacing(const RowLayout& layout);

/// Builds a field from an ordered layout (see order_layout_rows): vines every
/// config.vineyard.plant_spacing unless `instance` is given (then instanced every
/// config.layout.instance_spacing) or the layout lists explicit plants; posts, wires, weeds;
/// the ground from `terrain_mesh` if given, else from config.terrain.
Field dress_layout(const RowLayout& layout, const FieldConfig& config,
                   const TriangleMesh* instance = nullptr,
                   const TriangleMesh* terrain_mesh = nullptr);

}  // namespace rownav::sim
