#pragma once
/// @file field_config.hpp One config for any field: procedural vineyard / orchard / row crop, or
/// an imported layout dressed with vines. Imports need files: see io::build_field.
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/sim/field.hpp"
#include "rownav/sim/mesh_labels.hpp"
#include "rownav/sim/mesh_transform.hpp"
#include "rownav/sim/orchard.hpp"
#include "rownav/sim/row_crop.hpp"
#include "rownav/sim/terrain.hpp"
#include "rownav/sim/vineyard.hpp"

namespace rownav::sim {

/// Bounds on an imported layout, checked while it is read, before anything is dressed or cast:
/// one mistyped coordinate (latitude 0 instead of 51.5, a post at x = 4294967296) otherwise
/// makes rows thousands of km long, and dressing them runs for hours or exhausts memory.
struct LayoutLimits {
  /// [m] largest side of the box around every row point and plant (local frame): the largest
  /// vineyard and orchard blocks span ~2 km, and the flat local frame is meant for a field.
  double max_extent = 5000.0;
  /// [m] summed length of the rows kept: dressing time and memory grow with it (the whole
  /// 9 km AGRIDS vineyard takes ~3 s and ~0.4 GB, so 50 km ~15 s and ~2 GB).
  double max_total_row_length = 50000.0;
  int max_rows = 2000;  ///< [-] rows kept: 5 km at 2.5 m spacing
  /// [-] plants and posts listed in the layout file, each dressed like a vine: the vines of
  /// max_total_row_length at 1.2 m spacing
  int max_plants = 40000;
  /// [m] largest median distance between adjacent rows of a block (the corridor width the
  /// weeds are scattered over): orchards stay below 8 m; wider rows are no corridors.
  double max_row_spacing = 20.0;
  /// [-] deepest nesting of GeoJSON arrays / objects: a layout needs 8 (a MultiPolygon
  /// position); very deep nesting (~70,000) overflows the stack of the JSON library.
  int max_json_depth = 64;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("max_extent", s.max_extent);
    v("max_total_row_length", s.max_total_row_length);
    v("max_rows", s.max_rows);
    v("max_plants", s.max_plants);
    v("max_row_spacing", s.max_row_spacing);
    v("max_json_depth", s.max_json_depth);
  }
  void validate() const;
};

/// What dress_layout builds on an imported layout.
enum class LayoutDressing : std::uint8_t {
  plants,  ///< vines along the rows (or the listed plants), posts, wires, weeds, ground
  none,    ///< nothing: the meshes are the whole field (a photogrammetric mesh); the layout's
           ///< rows and plants are the ground truth only
};

/// An imported row layout (GeoJSON / CSV) and optional meshes. Rows are dressed with
/// FieldConfig::vineyard (its rows, row_length, row_spacing and curvature fields are unused;
/// the row spacing is estimated from the layout).
struct LayoutConfig {
  std::string file;               ///< CSV or GeoJSON layout, relative to the config file
  std::string instance_mesh;      ///< optional vine-row mesh instanced along rows (replaces vines)
  double instance_spacing = 5.1;  ///< [m] distance between instances along a row
  std::string terrain_mesh;       ///< optional whole terrain / field mesh (labelled ground),
                                  ///< replaces the procedural ground; the robot, plants and
                                  ///< posts stand on it (Terrain::drape)
  MeshTransform terrain_transform;  ///< places terrain_mesh in the layout frame (default: none)
  LayoutDressing dressing = LayoutDressing::plants;  ///< none: leave the meshes undressed
  MeshLabelConfig terrain_labels;  ///< labels terrain_mesh parts (default: all ground)
  std::vector<std::string> blocks;  ///< block names to keep (empty = all)
  double origin_lat_deg =
      std::numeric_limits<double>::quiet_NaN();  ///< [deg] ENU origin (NaN = first point)
  double origin_lon_deg =
      std::numeric_limits<double>::quiet_NaN();  ///< [deg] ENU origin (NaN = first point)
  LayoutLimits limits;  ///< bounds on the layout file (a typo must not hang the build)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("file", s.file);
    v("instance_mesh", s.instance_mesh);
    v("instance_spacing", s.instance_spacing);
    v("terrain_mesh", s.terrain_mesh);
    v("terrain_transform", s.terrain_transform);
    v("dressing", s.dressing);
    v("terrain_labels", s.terrain_labels);
    v("blocks", s.blocks);
    v("origin_lat_deg", s.origin_lat_deg);
    v("origin_lon_deg", s.origin_lon_deg);
    v("limits", s.limits);
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

/// [m] the configured row spacing of a procedural field (vineyard, orchard or row crop, the
/// crop preset resolved); 0 for kind layout (see estimate_row_spacing).
double nominal_row_spacing(const FieldConfig& config);

/// Builds a field from an ordered layout (see order_layout_rows): vines every
/// config.vineyard.plant_spacing unless `instance` is given (then instanced every
/// config.layout.instance_spacing) or the layout lists explicit plants (vines and posts dressed
/// with config.vineyard, trees with config.orchard, crop plants with config.row_crop, each
/// with its own sizes from layout.shapes); posts, wires, weeds; the ground from `terrain_mesh`
/// if given, else from config.terrain. With config.layout.dressing none only the meshes and the
/// listed plants (as ground truth) are kept.
Field dress_layout(const RowLayout& layout, const FieldConfig& config,
                   const TriangleMesh* instance = nullptr,
                   const TriangleMesh* terrain_mesh = nullptr);

}  // namespace rownav::sim

template <>
struct rownav::core::EnumNames<rownav::sim::LayoutDressing> {
  using E = rownav::sim::LayoutDressing;
  static constexpr std::array<std::pair<E, std::string_view>, 2> values{
      {{E::plants, "plants"}, {E::none, "none"}}};
};
