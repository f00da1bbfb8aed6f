#include "rownav/sim/row_crop.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rownav/sim/plant_geometry.hpp"
#include "rownav/sim/row_dressing.hpp"

namespace rownav::sim {
namespace {

using V3 = Eigen::Vector3f;

/// Maize: a 6-sided stalk and 5-7 arching leaves (~27 triangles).
void add_maize(TriangleMesh& m, const V3& b, float h, float w, std::mt19937_64& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  add_cylinder(m, b, b + V3(0, 0, h), 0.012f, 4, SurfaceClass::crop);
  const int leaves = 5 + static_cast<int>(u(rng) * 3.0f);
  for (int i = 0; i < leaves; ++i) {
    const float az = 2.0f * std::numbers::pi_v<float> * u(rng);
    const V3 dir(std::cos(az), std::sin(az), 0.0f);
    const float z = h * (0.2f + 0.7f * static_cast<float>(i) / leaves);
    const V3 root = b + V3(0, 0, z);
    const V3 tip = root + 0.5f * w * dir + V3(0, 0, 0.1f * h * (u(rng) - 0.3f));
    add_blade(m, root, tip, dir.cross(V3::UnitZ()), 0.07f, SurfaceClass::crop);
  }
}

/// Cabbage: a flattened jittered head plus 4 spread outer leaves (~28 triangles).
void add_cabbage(TriangleMesh& m, const V3& b, float h, float w, std::mt19937_64& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  add_blob(m, b + V3(0, 0, 0.5f * h), V3(0.3f * w, 0.3f * w, 0.5f * h), 0.2f, rng,
           SurfaceClass::crop);
  for (int i = 0; i < 4; ++i) {
    const float az = 0.5f * std::numbers::pi_v<float> * (static_cast<float>(i) + u(rng));
    const V3 dir(std::cos(az), std::sin(az), 0.0f);
    add_blade(m, b + V3(0, 0, 0.2f * h), b + 0.5f * w * dir + V3(0, 0, 0.6f * h),
              dir.cross(V3::UnitZ()), 0.25f * w, SurfaceClass::crop);
  }
}

/// Leek: a fan of 4-6 near-vertical blades in one plane (~15 triangles).
void add_leek(TriangleMesh& m, const V3& b, float h, float w, std::mt19937_64& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float az = std::numbers::pi_v<float> * u(rng);
  const V3 fan(std::cos(az), std::sin(az), 0.0f);
  const int blades = 4 + static_cast<int>(u(rng) * 3.0f);
  for (int i = 0; i < blades; ++i) {
    const float lean = (u(rng) - 0.5f) * w;
    add_blade(m, b, b + lean * fan + V3(0, 0, h * (0.7f + 0.3f * u(rng))), fan, 0.04f,
              SurfaceClass::crop);
  }
}

}  // namespace

CropPreset crop_preset(CropType crop) {
  switch (crop) {
    case CropType::cabbage:
      return {0.3, 0.45, 0.6, 0.45, 0.25};
    case CropType::leek:
      return {0.45, 0.13, 0.5, 0.12, 0.04};
    case CropType::maize:
      break;
  }
  return {0.6, 0.15, 0.75, 0.5, 0.03};
}

void add_crop_plant(TriangleMesh& mesh, const Eigen::Vector3f& base, CropType crop, float height,
                    float width, std::mt19937_64& rng) {
  if (crop == CropType::maize) add_maize(mesh, base, height, width, rng);
  if (crop == CropType::cabbage) add_cabbage(mesh, base, height, width, rng);
  if (crop == CropType::leek) add_leek(mesh, base, height, width, rng);
}

CropPreset RowCropConfig::resolved() const {
  CropPreset p = crop_preset(crop);
  if (plant_height > 0.0) p.plant_height = plant_height;
  if (plant_spacing > 0.0) p.plant_spacing = plant_spacing;
  if (row_spacing > 0.0) p.row_spacing = row_spacing;
  if (plant_width > 0.0) p.plant_width = plant_width;
  return p;
}

void RowCropConfig::validate() const {
  core::check_range(rows, 1, 2000, "rows");
  core::check_range(row_length, 1.0, 2000.0, "row_length");
  core::check_range(row_spacing, 0.0, 3.0, "row_spacing");
  core::check_range(plant_spacing, 0.0, 3.0, "plant_spacing");
  core::check_range(plant_height, 0.0, 3.0, "plant_height");
  core::check_range(plant_width, 0.0, 2.0, "plant_width");
  core::check_range(size_variation, 0.0, 0.5, "size_variation");
  core::check_range(missing_plants_percent, 0.0, 100.0, "missing_plants_percent");
  core::check_range(position_noise, 0.0, 0.5, "position_noise");
  core::check_range(curvature_amplitude, 0.0, 20.0, "curvature_amplitude");
  core::check_positive(curvature_wavelength, "curvature_wavelength");
  core::check_range(headland_width, 0.0, 100.0, "headland_width");
  core::check_range(weed_max_height, 0.0, 3.0, "weed_max_height");
  core::check_range(weed_max_radius, 0.0, 2.0, "weed_max_radius");
}

Field generate_row_crop(const RowCropConfig& config, const TerrainConfig& terrain,
                        std::uint64_t seed) {
  config.validate();
  const CropPreset p = config.resolved();
  std::mt19937_64 rng(seed);
  Field field = make_empty_field(std::string(core::enum_name(config.crop)), FieldKind::row_crop,
                                 p.row_spacing, config.headland_width, terrain);
  field.rows =
      make_parallel_rows(config.rows, config.row_length, p.row_spacing, config.curvature_amplitude,
                         config.curvature_wavelength, 0.5 * p.plant_width, p.plant_height, rng);
  std::bernoulli_distribution drop(config.missing_plants_percent / 100.0);
  std::normal_distribution<double> n01(0.0, 1.0);
  const int per_row =
      std::max(2, static_cast<int>(std::lround(config.row_length / p.plant_spacing)) + 1);
  const double step = config.row_length / (per_row - 1);
  for (const auto& row : field.rows) {
    const PolylinePath path(row.polyline);
    for (int i = 0; i < per_row; ++i) {
      const double scale = std::max(0.3, 1.0 + config.size_variation * n01(rng));
      const Eigen::Vector2d noise(config.position_noise * n01(rng),
                                  config.position_noise * n01(rng));
      if (drop(rng)) continue;
      const Eigen::Vector2d q = path.point(i * step) + noise;
      const V3 b(static_cast<float>(q.x()), static_cast<float>(q.y()),
                 static_cast<float>(field.terrain.height(q.x(), q.y())));
      const auto h = static_cast<float>(p.plant_height * scale);
      const auto w = static_cast<float>(p.plant_width * scale);
      add_crop_plant(field.mesh, b, config.crop, h, w, rng);
      field.plants.push_back({q, 0.5 * p.crush_diameter * scale, h, row.id, PlantKind::crop});
    }
  }
  scatter_weeds(field, config.weeds, p.row_spacing - 0.5 * p.plant_width,
                WeedSize{config.weed_max_height, config.weed_max_radius}, rng);
  add_ground(field);
  return field;
}

}  // namespace rownav::sim
