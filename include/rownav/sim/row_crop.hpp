#pragma once
/// @file row_crop.hpp Procedural row crop / market garden: small plants (maize, cabbage, leek)
/// in narrow rows, with per-crop presets.
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

/// Crop species; each has a plant model and a preset of dimensions.
enum class CropType : std::uint8_t { maize, cabbage, leek };

/// Typical dimensions of a crop (the preset used when a RowCropConfig field is 0).
struct CropPreset {
  double plant_height;   ///< [m]
  double plant_spacing;  ///< [m] along the row
  double row_spacing;    ///< [m]
  double plant_width;    ///< [m] diameter of the plant seen from above
  double crush_diameter; ///< [m] what a wheel crushes: maize / leek stem, cabbage head
};

/// Preset of a crop: maize 0.6 m tall, 0.15 m apart, rows 0.75 m; cabbage 0.3 m, 0.45 m, 0.6 m;
/// leek 0.45 m, 0.13 m, 0.5 m. Leaves may be brushed; only the stem (head) counts as crushed.
CropPreset crop_preset(CropType crop);

/// Row-crop geometry. Rows run along +x from x = 0, row k at y = k * row_spacing.
/// Dimension fields left at 0 take the crop's preset.
struct RowCropConfig {
  CropType crop = CropType::maize;      ///< species (plant model and presets)
  int rows = 12;                        ///< [-] number of rows
  double row_length = 40.0;             ///< [m] first to last plant
  double row_spacing = 0.0;             ///< [m] between rows (0 = preset; 0.5-0.9 typical)
  double plant_spacing = 0.0;           ///< [m] along the row (0 = preset; 0.13-0.5 typical)
  double plant_height = 0.0;            ///< [m] mean height (0 = preset; 0.2-0.6 typical)
  double plant_width = 0.0;             ///< [m] mean plant diameter (0 = preset)
  double size_variation = 0.15;         ///< [-] relative std-dev of plant size
  double missing_plants_percent = 5.0;  ///< [%] plants missing at random
  double position_noise = 0.02;         ///< [m] std-dev of the plant position around its slot
  double curvature_amplitude = 0.0;     ///< [m] lateral sine bend of the rows
  double curvature_wavelength = 60.0;   ///< [m] wavelength of the bend
  double headland_width = 4.0;          ///< [m] free ground beyond the row ends
  WeedLevel weeds = WeedLevel::none;    ///< inter-row weeds
  /// [m] tallest weed (0 = the level's preset: some 0.25 m, many 0.5 m, sized for vineyards).
  /// Malavazi 2018's market garden has weeds the size of its 20 x 20 cm simulator patches.
  double weed_max_height = 0.0;
  double weed_max_radius = 0.0;  ///< [m] widest weed (0 = the level's preset, 0.15 / 0.25 m)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("crop", s.crop);
    v("rows", s.rows);
    v("row_length", s.row_length);
    v("row_spacing", s.row_spacing);
    v("plant_spacing", s.plant_spacing);
    v("plant_height", s.plant_height);
    v("plant_width", s.plant_width);
    v("size_variation", s.size_variation);
    v("missing_plants_percent", s.missing_plants_percent);
    v("position_noise", s.position_noise);
    v("curvature_amplitude", s.curvature_amplitude);
    v("curvature_wavelength", s.curvature_wavelength);
    v("headland_width", s.headland_width);
    v("weeds", s.weeds);
    v("weed_max_height", s.weed_max_height);
    v("weed_max_radius", s.weed_max_radius);
  }
  void validate() const;
  /// The dimensions in effect: the fields, with 0 replaced by the crop preset.
  CropPreset resolved() const;
};

/// Adds one plant of `crop` (height x width [m]) standing at ground point `base`, labelled crop.
void add_crop_plant(TriangleMesh& mesh, const Eigen::Vector3f& base, CropType crop, float height,
                    float width, std::mt19937_64& rng);

/// Generates a row-crop field (plants kind crop, mesh label crop). Deterministic in seed.
/// @throws std::invalid_argument when a config is invalid (naming the field)
Field generate_row_crop(const RowCropConfig& config, const TerrainConfig& terrain,
                        std::uint64_t seed);

}  // namespace rownav::sim

template <>
struct rownav::core::EnumNames<rownav::sim::CropType> {
  using E = rownav::sim::CropType;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::maize, "maize"}, {E::cabbage, "cabbage"}, {E::leek, "leek"}}};
};
