#pragma once
/// @file orchard.hpp Procedural orchard: rows of trees with trunks and jittered clumped crowns.
#include <array>
#include <cstdint>
#include <random>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"
#include "rownav/sim/field.hpp"
#include "rownav/sim/terrain.hpp"
#include "rownav/sim/vineyard.hpp"

namespace rownav::sim {

/// Training system of the trees.
enum class OrchardForm : std::uint8_t {
  free_standing,  ///< separate round crowns (standard / half-standard trees)
  hedgerow,       ///< fruit wall: crowns stretched along the row into a continuous hedge
};

/// Orchard geometry. Rows run along +x from x = 0, row k at y = k * row_spacing.
struct OrchardConfig {
  int rows = 6;                         ///< [-] number of rows
  double row_length = 60.0;             ///< [m] from first to last tree
  double row_spacing = 5.0;             ///< [m] between row centre lines (3.5-6)
  double tree_spacing = 4.0;            ///< [m] between trees along the row (3.5-6)
  double trunk_diameter = 0.15;         ///< [m]
  double trunk_height = 0.8;            ///< [m] ground to the crown's lowest branches
  double crown_diameter = 2.5;          ///< [m] mean crown width
  double crown_height = 2.5;            ///< [m] mean crown vertical extent
  double size_variation = 0.2;          ///< [-] relative std-dev of crown size from tree to tree
  double missing_trees_percent = 3.0;   ///< [%] trees missing at random
  double curvature_amplitude = 0.0;     ///< [m] lateral sine bend of the rows
  double curvature_wavelength = 100.0;  ///< [m] wavelength of the bend
  double headland_width = 8.0;          ///< [m] free ground beyond the row ends
  WeedLevel weeds = WeedLevel::some;    ///< inter-row grass and weeds
  /// free_standing or hedgerow (issue 10: apple fruit walls, crowns 1-1.5 m wide, trees 1-1.5 m)
  OrchardForm form = OrchardForm::free_standing;
  /// [-] hedgerow: crown semi-axis along the row as a fraction of tree_spacing (0.75: crowns of
  /// neighbours overlap by half a spacing, no see-through gap); free_standing: unused
  double hedge_overlap = 0.75;
  double trunk_variation = 0.0;  ///< [-] relative std-dev of the trunk diameter (issue 10: 0.1-0.3 m)
  double position_jitter = 0.0;  ///< [m] std-dev of each tree's position around its slot
  int gap_count = 0;             ///< [-] runs of consecutive missing trees in random rows
  int gap_length_trees = 4;      ///< [-] trees missing in each run (issue 10: gaps up to ~20 m)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("rows", s.rows);
    v("row_length", s.row_length);
    v("row_spacing", s.row_spacing);
    v("tree_spacing", s.tree_spacing);
    v("trunk_diameter", s.trunk_diameter);
    v("trunk_height", s.trunk_height);
    v("crown_diameter", s.crown_diameter);
    v("crown_height", s.crown_height);
    v("size_variation", s.size_variation);
    v("missing_trees_percent", s.missing_trees_percent);
    v("curvature_amplitude", s.curvature_amplitude);
    v("curvature_wavelength", s.curvature_wavelength);
    v("headland_width", s.headland_width);
    v("weeds", s.weeds);
    v("form", s.form);
    v("hedge_overlap", s.hedge_overlap);
    v("trunk_variation", s.trunk_variation);
    v("position_jitter", s.position_jitter);
    v("gap_count", s.gap_count);
    v("gap_length_trees", s.gap_length_trees);
  }
  void validate() const;
};

/// Adds one tree standing at ground point `base`: an 8-sided trunk (trunk_diameter) up into a
/// crown of 6-10 jittered clumps (crown_diameter x crown_height, scaled per tree by
/// size_variation) above trunk_height. The orchard generator and imported layouts use it.
/// `along_radius` > 0 (hedgerow) stretches the crown to that semi-axis [m] along the unit row
/// direction `along`.
/// @return [m] top of the tree above the ground
double add_tree(TriangleMesh& mesh, const Eigen::Vector3f& base, const OrchardConfig& config,
                std::mt19937_64& rng, const Eigen::Vector2d& along = Eigen::Vector2d::UnitX(),
                double along_radius = 0.0);

/// Generates an orchard (trees kind tree; trunk + 6-10 crown clumps each). Deterministic in seed.
/// @throws std::invalid_argument when a config is invalid (naming the field)
Field generate_orchard(const OrchardConfig& config, const TerrainConfig& terrain,
                       std::uint64_t seed);

}  // namespace rownav::sim

template <>
struct rownav::core::EnumNames<rownav::sim::OrchardForm> {
  using E = rownav::sim::OrchardForm;
  static constexpr std::array<std::pair<E, std::string_view>, 2> values{
      {{E::free_standing, "free_standing"}, {E::hedgerow, "hedgerow"}}};
};
