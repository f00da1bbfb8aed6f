#pragma once
/// @file vineyard.hpp Procedural vineyard with a vertical shoot position (VSP) trellis: trunks,
/// clumped irregular canopy with protruding shoots, posts, wires, missing vines and inter-row
/// weeds. Canopy density by growth stage follows the BACCHUS vineyard models (low = sparse
/// young shoots, medium, high = dense full wall).
#include <array>
#include <cstdint>
#include <random>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"
#include "rownav/sim/field.hpp"
#include "rownav/sim/terrain.hpp"

namespace rownav::sim {

/// Canopy growth stage.
enum class GrowthStage : std::uint8_t { low, medium, high };
/// Amount of inter-row grass and weeds.
enum class WeedLevel : std::uint8_t { none, some, many };
/// How the canopy is built: VSP foliage clumps over visible trunks, or a solid hedge (issue 10:
/// a real photogrammetric vineyard mesh is a continuous mound from the ground up, no trunk zone).
enum class CanopyShape : std::uint8_t { clumps, solid_hedge };

/// Vineyard geometry. Rows run along +x from x = 0, row k at y = k * row_spacing.
struct VineyardConfig {
  int rows = 10;                   ///< [-] number of rows
  double row_length = 50.0;        ///< [m] from end post to end post
  double row_spacing = 2.0;        ///< [m] between row centre lines (narrow 1.5-1.9, wide 2.5-3)
  double plant_spacing = 1.0;      ///< [m] between vines along the row
  double trunk_diameter = 0.06;    ///< [m]
  double cordon_height_min = 0.3;  ///< [m] lowest cordon (top of trunk) above the ground
  double cordon_height_max = 0.6;  ///< [m] highest cordon
  double canopy_top = 1.8;         ///< [m] top of the full-grown canopy above the ground
  double canopy_width = 0.5;       ///< [m] mean canopy wall thickness across the row
  GrowthStage stage = GrowthStage::medium;  ///< canopy density
  double shoot_protrusion = 0.3;            ///< [m] max reach of shoots beyond the canopy wall
  double post_spacing = 5.5;                ///< [m] between intermediate trellis posts
  double post_diameter = 0.08;              ///< [m] intermediate post
  double end_post_diameter = 0.14;          ///< [m] stronger post at each row end
  bool wires = true;                        ///< model the trellis wires
  int wire_count = 3;                       ///< [-] wires from the cordon up to the canopy top
  double wire_diameter = 0.004;             ///< [m]
  double missing_plants_percent = 3.0;      ///< [%] vines missing at random (besides the gaps)
  int gap_count = 1;                        ///< [-] longer gaps in the whole field (random rows)
  int gap_length_plants = 3;                ///< [-] consecutive vines missing in each gap
  double curvature_amplitude = 0.0;    ///< [m] lateral sine bend of the rows (same for all rows)
  double curvature_wavelength = 80.0;  ///< [m] wavelength of the bend
  double headland_width = 6.0;         ///< [m] free ground beyond the row ends
  WeedLevel weeds = WeedLevel::none;   ///< inter-row grass and weeds
  /// clumps: trunks, cordon, foliage clumps (stage); solid_hedge: each vine is a closed mound
  /// segment from the ground to ~canopy_top, canopy_width wide at the ground (stage, shoots and
  /// trunk heights unused; posts and wires stay inside). Issue 10, a real vineyard mesh.
  CanopyShape canopy_shape = CanopyShape::clumps;
  /// [-] solid_hedge cross-section |y / half_width|^p + (z / top)^p = 1: 2 = half ellipse (a
  /// rounded mound, issue 10), 4 = steep faces and a flat crown, large = a box wall (rownav)
  double hedge_roundness = 2.0;
  /// [-] solid_hedge surface roughness: each profile vertex moves across the row by up to this
  /// fraction of the half width; vine-to-vine vigour varies the width +-10 % (rownav)
  double hedge_roughness = 0.1;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("rows", s.rows);
    v("row_length", s.row_length);
    v("row_spacing", s.row_spacing);
    v("plant_spacing", s.plant_spacing);
    v("trunk_diameter", s.trunk_diameter);
    v("cordon_height_min", s.cordon_height_min);
    v("cordon_height_max", s.cordon_height_max);
    v("canopy_top", s.canopy_top);
    v("canopy_width", s.canopy_width);
    v("stage", s.stage);
    v("shoot_protrusion", s.shoot_protrusion);
    v("post_spacing", s.post_spacing);
    v("post_diameter", s.post_diameter);
    v("end_post_diameter", s.end_post_diameter);
    v("wires", s.wires);
    v("wire_count", s.wire_count);
    v("wire_diameter", s.wire_diameter);
    v("missing_plants_percent", s.missing_plants_percent);
    v("gap_count", s.gap_count);
    v("gap_length_plants", s.gap_length_plants);
    v("curvature_amplitude", s.curvature_amplitude);
    v("curvature_wavelength", s.curvature_wavelength);
    v("headland_width", s.headland_width);
    v("weeds", s.weeds);
    v("canopy_shape", s.canopy_shape);
    v("hedge_roundness", s.hedge_roundness);
    v("hedge_roughness", s.hedge_roughness);
  }
  void validate() const;
};

/// Generates a vineyard on the given terrain. Deterministic in `seed`.
/// @throws std::invalid_argument when a config is invalid (naming the field)
Field generate_vineyard(const VineyardConfig& config, const TerrainConfig& terrain,
                        std::uint64_t seed);

}  // namespace rownav::sim

template <>
struct rownav::core::EnumNames<rownav::sim::GrowthStage> {
  using E = rownav::sim::GrowthStage;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::low, "low"}, {E::medium, "medium"}, {E::high, "high"}}};
};

template <>
struct rownav::core::EnumNames<rownav::sim::WeedLevel> {
  using E = rownav::sim::WeedLevel;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::none, "none"}, {E::some, "some"}, {E::many, "many"}}};
};

template <>
struct rownav::core::EnumNames<rownav::sim::CanopyShape> {
  using E = rownav::sim::CanopyShape;
  static constexpr std::array<std::pair<E, std::string_view>, 2> values{
      {{E::clumps, "clumps"}, {E::solid_hedge, "solid_hedge"}}};
};

namespace rownav::sim {

/// Adds one vine standing at ground point `base` of a row heading along unit `tangent`: an
/// 8-sided trunk up to a random cordon height in [cordon_height_min, cordon_height_max], a
/// cordon arm along the row, jittered foliage clumps (count, size and top by `config.stage`) and
/// shoots protruding up to `config.shoot_protrusion` beyond the wall.
/// With `config.canopy_shape == solid_hedge` adds add_hedge_segment() instead.
/// @return [m] top of this vine's canopy above the ground
double add_vine(TriangleMesh& mesh, const Eigen::Vector3d& base, const Eigen::Vector2d& tangent,
                const VineyardConfig& config, std::mt19937_64& rng);

/// Adds one plant_spacing long piece of a solid hedge centred on ground point `base` of a row
/// heading along unit `tangent`: a closed prism whose cross-section is the superellipse of
/// `config.hedge_roundness` from the ground (0.05 m below, so no gap shows over rough ground)
/// to ~canopy_top, rough by `config.hedge_roughness`, with end caps (gaps and row ends show the
/// cross-section). Pieces overlap 2 cm so a continuous row has no cracks.
/// @return [m] top of this piece above the ground
double add_hedge_segment(TriangleMesh& mesh, const Eigen::Vector3d& base,
                         const Eigen::Vector2d& tangent, const VineyardConfig& config,
                         std::mt19937_64& rng);

}  // namespace rownav::sim
