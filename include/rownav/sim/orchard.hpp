#pragma once
/// @file orchard.hpp Procedural orchard: rows of trees with trunks and jittered clumped crowns.
#include <cstdint>
#include <random>

#include "rownav/core/config_fields.hpp"
#include "rownav/sim/field.hpp"
#include "rownav/sim/terrain.hpp"
#include "rownav/sim/vineyard.hpp"

namespace rownav::sim {

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
  }
  void validate() const;
};

/// Adds one tree standing at ground point `base`: an 8-sided trunk (trunk_diameter) up into a
/// crown of 6-10 jittered clumps (crown_diameter x crown_height, scaled per tree by
/// size_variation) above trunk_height. The orchard generator and imported layouts use it.
/// @return [m] top of the tree above the ground
double add_tree(TriangleMesh& mesh, const Eigen::Vector3f& base, const OrchardConfig& config,
                std::mt19937_64& rng);

/// Generates an orchard (trees kind tree; trunk + 6-10 crown clumps each). Deterministic in seed.
/// @throws std::invalid_argument when a config is invalid (naming the field)
Field generate_orchard(const OrchardConfig& config, const TerrainConfig& terrain,
                       std::uint64_t seed);

}  // namespace rownav::sim
