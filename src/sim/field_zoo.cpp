#include "rownav/sim/field_zoo.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <random>
#include <stdexcept>

#include "rownav/core/angle.hpp"

namespace rownav::sim {
namespace {

using Rng = std::mt19937_64;

double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
bool chance(Rng& rng, double p) { return std::bernoulli_distribution(p)(rng); }
WeedLevel any_weeds(Rng& rng) {
  return static_cast<WeedLevel>(std::uniform_int_distribution<int>(0, 2)(rng));
}
double degrees_of_percent(double percent) { return core::rad2deg(std::atan(percent / 100.0)); }

/// Slope, roughness and seed of the ground.
void draw_terrain(FieldConfig& f, const ZooConfig& z, Rng& rng) {
  f.terrain.slope_x_deg = degrees_of_percent(uniform(rng, -z.max_slope_percent, z.max_slope_percent));
  f.terrain.slope_y_deg = degrees_of_percent(uniform(rng, -z.max_slope_percent, z.max_slope_percent));
  f.terrain.roughness = uniform(rng, 0.0, z.max_roughness);
  f.terrain.seed = rng();
}

/// Lateral sine bend (amplitude, wavelength) for a curved_share of the fields, else straight.
std::array<double, 2> draw_bend(const ZooConfig& z, Rng& rng) {
  if (!chance(rng, z.curved_share)) return {0.0, 100.0};
  return {uniform(rng, 0.2, z.max_curvature), uniform(rng, z.bend_wavelength_min, z.bend_wavelength_max)};
}

void draw_vineyard(FieldConfig& f, const ZooConfig& z, bool wide, double length, Rng& rng) {
  VineyardConfig& v = f.vineyard;
  f.kind = FieldKind::vineyard;
  v.rows = z.rows, v.row_length = length;
  v.row_spacing = wide ? uniform(rng, z.vine_narrow_max, z.vine_wide_max)
                       : uniform(rng, z.vine_narrow_min, z.vine_narrow_max);
  v.stage = static_cast<GrowthStage>(std::uniform_int_distribution<int>(0, 2)(rng));
  if (chance(rng, z.solid_hedge_share)) v.canopy_shape = CanopyShape::solid_hedge;
  v.canopy_width = uniform(rng, 0.35, std::min(0.8, 0.45 * v.row_spacing));
  v.gap_length_plants = std::max(1, static_cast<int>(uniform(rng, 1.0, z.max_gap_length) / v.plant_spacing));
  v.gap_count = std::uniform_int_distribution<int>(0, 3)(rng);
  const auto [a, w] = draw_bend(z, rng);
  v.curvature_amplitude = a, v.curvature_wavelength = w;
  v.weeds = any_weeds(rng);
}

void draw_orchard(FieldConfig& f, const ZooConfig& z, bool hedge, double length, Rng& rng) {
  OrchardConfig& o = f.orchard;
  f.kind = FieldKind::orchard;
  o.rows = z.rows, o.row_length = length;
  o.form = hedge ? OrchardForm::hedgerow : OrchardForm::free_standing;
  o.row_spacing = uniform(rng, z.orchard_row_min, hedge ? z.hedge_row_max : z.orchard_row_max);
  o.tree_spacing = hedge ? uniform(rng, z.hedge_tree_min, z.hedge_tree_max)
                         : uniform(rng, z.tree_spacing_min, z.tree_spacing_max);
  o.trunk_diameter = uniform(rng, z.trunk_min, z.trunk_max);
  o.trunk_variation = 0.15;
  o.crown_diameter = hedge ? uniform(rng, z.crown_min, z.hedge_crown_max)
                           : uniform(rng, z.crown_min,
                                     std::min(z.crown_max, o.row_spacing - z.crown_clearance));
  o.crown_height = uniform(rng, 1.5, 3.0);
  o.position_jitter = uniform(rng, 0.0, 0.15);
  o.gap_count = std::uniform_int_distribution<int>(0, 2)(rng);
  o.gap_length_trees = std::max(1, static_cast<int>(uniform(rng, o.tree_spacing, z.max_gap_length) / o.tree_spacing));
  const auto [a, w] = draw_bend(z, rng);
  o.curvature_amplitude = a, o.curvature_wavelength = w;
  o.weeds = any_weeds(rng);
}

void draw_row_crop(FieldConfig& f, const ZooConfig& z, double length, Rng& rng) {
  RowCropConfig& c = f.row_crop;
  f.kind = FieldKind::row_crop;
  c.crop = static_cast<CropType>(std::uniform_int_distribution<int>(0, 2)(rng));
  c.rows = z.rows, c.row_length = length;
  c.row_spacing = uniform(rng, z.crop_row_min, z.crop_row_max);
  c.missing_plants_percent = uniform(rng, 0.0, 10.0);
  const auto [a, w] = draw_bend(z, rng);
  c.curvature_amplitude = a, c.curvature_wavelength = w;
  c.weeds = any_weeds(rng);
}

}  // namespace

void ZooConfig::validate() const {
  core::check_range(rows, 2, 100, "rows");
  core::check_range(row_length_min, 5.0, 500.0, "row_length_min");
  core::check_range(row_length_max, row_length_min, 500.0, "row_length_max");
  core::check_range(vine_narrow_min, 1.0, 5.0, "vine_narrow_min");
  core::check_range(vine_narrow_max, vine_narrow_min, 5.0, "vine_narrow_max");
  core::check_range(vine_wide_max, vine_narrow_max, 5.0, "vine_wide_max");
  core::check_range(solid_hedge_share, 0.0, 1.0, "solid_hedge_share");
  core::check_range(orchard_row_min, 3.0, 15.0, "orchard_row_min");
  core::check_range(orchard_row_max, orchard_row_min, 15.0, "orchard_row_max");
  core::check_range(tree_spacing_min, 0.5, 15.0, "tree_spacing_min");
  core::check_range(tree_spacing_max, tree_spacing_min, 15.0, "tree_spacing_max");
  core::check_range(hedge_tree_min, 0.5, 15.0, "hedge_tree_min");
  core::check_range(hedge_tree_max, hedge_tree_min, 15.0, "hedge_tree_max");
  core::check_range(crop_row_min, 0.2, 3.0, "crop_row_min");
  core::check_range(crop_row_max, crop_row_min, 3.0, "crop_row_max");
  core::check_range(max_slope_percent, 0.0, 50.0, "max_slope_percent");
  core::check_range(max_curvature, 0.2, 20.0, "max_curvature");
  core::check_range(curved_share, 0.0, 1.0, "curved_share");
  core::check_range(max_gap_length, 1.0, 100.0, "max_gap_length");
  core::check_range(hedge_row_max, orchard_row_min, 15.0, "hedge_row_max");
  core::check_range(trunk_min, 0.02, 1.0, "trunk_min");
  core::check_range(trunk_max, trunk_min, 1.0, "trunk_max");
  core::check_range(crown_min, 0.2, 10.0, "crown_min");
  core::check_range(crown_max, crown_min, 10.0, "crown_max");
  core::check_range(hedge_crown_max, crown_min, 10.0, "hedge_crown_max");
  core::check_range(crown_clearance, 0.0, orchard_row_min - crown_min, "crown_clearance");
  core::check_range(max_roughness, 0.0, 1.0, "max_roughness");
  core::check_range(bend_wavelength_min, 10.0, 1000.0, "bend_wavelength_min");
  core::check_range(bend_wavelength_max, bend_wavelength_min, 1000.0, "bend_wavelength_max");
}

std::string_view zoo_band_name(int band) {
  static constexpr std::array<std::string_view, kZooBands> names = {
      "vineyard_narrow", "vineyard_wide", "orchard_free", "orchard_hedgerow", "row_crop"};
  if (band < 0 || band >= kZooBands) throw std::invalid_argument("band: out of range");
  return names[static_cast<std::size_t>(band)];
}

FieldConfig zoo_field(int index, std::uint64_t seed, const ZooConfig& config) {
  config.validate();
  if (index < 0) throw std::invalid_argument("index: must be >= 0");
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(index)};
  Rng rng(seq);
  const int band = index % kZooBands;
  FieldConfig f;
  f.name = "zoo_" + std::to_string(seed) + "_" + std::to_string(index) + "_";
  f.name.append(zoo_band_name(band));
  f.seed = rng();
  const double length = uniform(rng, config.row_length_min, config.row_length_max);
  if (band <= 1) draw_vineyard(f, config, band == 1, length, rng);
  else if (band <= 3) draw_orchard(f, config, band == 3, length, rng);
  else draw_row_crop(f, config, length, rng);
  draw_terrain(f, config, rng);
  f.validate();
  return f;
}

std::string zoo_ref_text(const ZooRef& ref) {
  return "zoo:" + std::to_string(ref.seed) + ":" + std::to_string(ref.index);
}

std::optional<ZooRef> parse_zoo_ref(std::string_view text) {
  constexpr std::string_view prefix = "zoo:";
  if (!text.starts_with(prefix)) return std::nullopt;
  text.remove_prefix(prefix.size());
  const auto colon = text.find(':');
  if (colon == std::string_view::npos) return std::nullopt;
  ZooRef ref;
  const auto whole = [](std::string_view s, auto& value) {
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    return ec == std::errc() && end == s.data() + s.size() && !s.empty();
  };
  if (!whole(text.substr(0, colon), ref.seed) || !whole(text.substr(colon + 1), ref.index) ||
      ref.index < 0)
    return std::nullopt;
  return ref;
}

std::string field_label(const std::filesystem::path& field) {
  if (const auto ref = parse_zoo_ref(field.string())) return zoo_field(ref->index, ref->seed).name;
  return field.stem().string();
}

}  // namespace rownav::sim
