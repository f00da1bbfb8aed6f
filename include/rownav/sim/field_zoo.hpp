#pragma once
/// @file field_zoo.hpp A seeded zoo of random row-structured fields (issue 10: "a zoo of fields,
/// measured"): vineyards narrow to wide with thin to solid canopy, free-standing and hedgerow
/// orchards, row crops; spacing 0.5-7 m, gaps, slopes, curvature, weeds.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "rownav/core/config_fields.hpp"
#include "rownav/sim/field_config.hpp"

namespace rownav::sim {

/// The bands the zoo draws from. Field i belongs to band i % 5 (vineyard_narrow,
/// vineyard_wide, orchard_free, orchard_hedgerow, row_crop), so any 5 consecutive fields cover
/// every crop kind; everything else is drawn from the seed.
struct ZooConfig {
  int rows = 6;                        ///< [-] rows per field (5 corridors)
  double row_length_min = 30.0;        ///< [m] shortest row
  double row_length_max = 60.0;        ///< [m] longest row
  double vine_narrow_min = 1.5;        ///< [m] narrow vineyard row spacing (issue 10: 1.5-1.75)
  double vine_narrow_max = 2.0;        ///< [m]
  double vine_wide_max = 3.0;          ///< [m] wide vineyards: vine_narrow_max to this
  double solid_hedge_share = 0.5;      ///< [-] vineyards with a solid hedge canopy
  double orchard_row_min = 3.0;        ///< [m] orchard row spacing (issue 10: 3-7)
  double orchard_row_max = 7.0;        ///< [m]
  double tree_spacing_min = 3.0;       ///< [m] free-standing trees (issue 10: 1-6, walls 1-1.5)
  double tree_spacing_max = 6.0;       ///< [m]
  double hedge_tree_min = 1.0;         ///< [m] hedgerow tree spacing
  double hedge_tree_max = 1.5;         ///< [m]
  double crop_row_min = 0.5;           ///< [m] row-crop spacing (maize, cabbage, leek presets)
  double crop_row_max = 0.9;           ///< [m]
  double max_slope_percent = 15.0;     ///< [%] steepest slope along or across the rows
  double max_curvature = 1.5;          ///< [m] largest lateral bend amplitude of the rows
  double curved_share = 0.3;           ///< [-] fields with curved rows
  double max_gap_length = 20.0;        ///< [m] longest in-row gap (several missing plants)
  double hedge_row_max = 4.5;          ///< [m] widest hedgerow orchard row spacing (fruit walls stand 3-4.5 m apart)
  double trunk_min = 0.1;              ///< [m] thinnest mean tree trunk (issue 10: 0.1-0.3)
  double trunk_max = 0.3;              ///< [m] thickest
  double crown_min = 1.0;              ///< [m] narrowest tree crown (issue 10: 1-4; hedgerows up to hedge_crown_max)
  double crown_max = 4.0;              ///< [m] widest (and at most the row spacing - crown_clearance)
  double hedge_crown_max = 1.5;        ///< [m] widest hedgerow crown
  double crown_clearance = 1.5;        ///< [m] free corridor left between crowns
  double max_roughness = 0.05;         ///< [m] roughest ground (TerrainConfig::roughness)
  double bend_wavelength_min = 60.0;   ///< [m] shortest wavelength of a row bend
  double bend_wavelength_max = 120.0;  ///< [m] longest

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("rows", s.rows);
    v("row_length_min", s.row_length_min);
    v("row_length_max", s.row_length_max);
    v("vine_narrow_min", s.vine_narrow_min);
    v("vine_narrow_max", s.vine_narrow_max);
    v("vine_wide_max", s.vine_wide_max);
    v("solid_hedge_share", s.solid_hedge_share);
    v("orchard_row_min", s.orchard_row_min);
    v("orchard_row_max", s.orchard_row_max);
    v("tree_spacing_min", s.tree_spacing_min);
    v("tree_spacing_max", s.tree_spacing_max);
    v("hedge_tree_min", s.hedge_tree_min);
    v("hedge_tree_max", s.hedge_tree_max);
    v("crop_row_min", s.crop_row_min);
    v("crop_row_max", s.crop_row_max);
    v("max_slope_percent", s.max_slope_percent);
    v("max_curvature", s.max_curvature);
    v("curved_share", s.curved_share);
    v("max_gap_length", s.max_gap_length);
    v("hedge_row_max", s.hedge_row_max);
    v("trunk_min", s.trunk_min);
    v("trunk_max", s.trunk_max);
    v("crown_min", s.crown_min);
    v("crown_max", s.crown_max);
    v("hedge_crown_max", s.hedge_crown_max);
    v("crown_clearance", s.crown_clearance);
    v("max_roughness", s.max_roughness);
    v("bend_wavelength_min", s.bend_wavelength_min);
    v("bend_wavelength_max", s.bend_wavelength_max);
  }
  void validate() const;
};

/// Number of bands (field i is in band i % kZooBands).
inline constexpr int kZooBands = 5;

/// Name of band `band` (0 .. kZooBands - 1): vineyard_narrow, vineyard_wide, orchard_free,
/// orchard_hedgerow, row_crop.
std::string_view zoo_band_name(int band);

/// Field `index` (>= 0) of the zoo of `seed`: a procedural FieldConfig, named
/// zoo_<seed>_<index>_<band>, that validates. The same (index, seed, config) always gives the
/// same config; fields of different indices are independent draws.
/// @throws std::invalid_argument for a negative index or an invalid config
FieldConfig zoo_field(int index, std::uint64_t seed, const ZooConfig& config = {});

/// A zoo field named by reference instead of a file: "zoo:SEED:INDEX" (`rownav run --field
/// zoo:1:17`, bench scenario matrices' `zoo_count`).
struct ZooRef {
  std::uint64_t seed = 1;  ///< zoo seed
  int index = 0;           ///< field index (>= 0)
};

/// "zoo:SEED:INDEX".
std::string zoo_ref_text(const ZooRef& ref);

/// The reference in `text` when it is one ("zoo:" then two non-negative integers), else nullopt.
std::optional<ZooRef> parse_zoo_ref(std::string_view text);

/// A field's label in reports and tables: the zoo field's name for a reference
/// (zoo_<seed>_<index>_<band>), else the file's stem.
std::string field_label(const std::filesystem::path& field);

}  // namespace rownav::sim
