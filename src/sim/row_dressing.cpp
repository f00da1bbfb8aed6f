#include "rownav/sim/row_dressing.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <numbers>

#include "rownav/sim/plant_geometry.hpp"

namespace rownav::sim {
namespace {

constexpr double kWirePiece = 1.0;  // [m] longest wire segment (keeps BVH boxes tight)

Eigen::Vector3f ground_point(const Terrain& t, const Eigen::Vector2d& p, double dz = 0.0) {
  return {static_cast<float>(p.x()), static_cast<float>(p.y()),
          static_cast<float>(t.height(p.x(), p.y()) + dz)};
}

/// Vine arcs of a row: every `spacing`, the first and last half a spacing from the ends.
std::vector<double> vine_arcs(double length, double spacing) {
  std::vector<double> out;
  for (double s = 0.5 * spacing; s <= length - 0.5 * spacing + 1e-9; s += spacing) out.push_back(s);
  return out;
}

/// Marks `gap_count` runs of `gap_length` consecutive vines as missing in random rows.
void mark_gaps(std::vector<std::vector<bool>>& missing, int gap_count, int gap_length,
               std::mt19937_64& rng) {
  std::uniform_int_distribution<std::size_t> pick_row(0, missing.size() - 1);
  for (int g = 0, tries = 0; g < gap_count && tries < 100 * gap_count; ++tries) {
    auto& row = missing[pick_row(rng)];
    const auto len = static_cast<std::size_t>(gap_length);
    if (row.size() < len + 2) continue;
    // Keep a planted vine on both sides so the gap has exactly the configured length.
    std::uniform_int_distribution<std::size_t> pick(1, row.size() - len - 1);
    const std::size_t a = pick(rng);
    if (std::any_of(row.begin() + a - 1, row.begin() + a + len + 1, [](bool m) { return m; }))
      continue;
    std::fill(row.begin() + a, row.begin() + a + len, true);
    ++g;
  }
}

}  // namespace

Field make_empty_field(std::string name, FieldKind kind, double row_spacing,
                       double headland_width, const TerrainConfig& terrain) {
  Field field;
  field.name = std::move(name);
  field.kind = kind;
  field.row_spacing = row_spacing;
  field.headland_width = headland_width;
  field.terrain = Terrain(terrain);
  return field;
}

std::vector<Row> make_parallel_rows(int count, double length, double spacing, double amplitude,
                                    double wavelength, double half_width, double height,
                                    std::mt19937_64& rng) {
  std::uniform_real_distribution<double> phase_dist(0.0, 2.0 * std::numbers::pi);
  const double phase = phase_dist(rng);
  const int n = std::max(1, static_cast<int>(std::ceil(length)));
  std::vector<Row> rows(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    Row& r = rows[static_cast<std::size_t>(k)];
    r.id = k;
    r.half_width = half_width;
    r.height = height;
    for (int i = 0; i <= n; ++i) {
      const double x = length * i / n;
      const double bend = amplitude * std::sin(2.0 * std::numbers::pi * x / wavelength + phase);
      r.polyline.emplace_back(x, k * spacing + bend);
    }
  }
  return rows;
}

std::vector<double> post_arcs(double length, double spacing) {
  const int n = std::max(1, static_cast<int>(std::lround(length / spacing)));
  std::vector<double> out;
  for (int j = 0; j <= n; ++j) out.push_back(length * j / n);
  return out;
}

void place_vines(Field& field, const VineyardConfig& c, std::mt19937_64& rng) {
  std::vector<std::vector<bool>> missing;
  for (const auto& row : field.rows)
    missing.emplace_back(vine_arcs(PolylinePath(row.polyline).length(), c.plant_spacing).size(),
                         false);
  if (!missing.empty()) mark_gaps(missing, c.gap_count, c.gap_length_plants, rng);
  std::bernoulli_distribution drop(c.missing_plants_percent / 100.0);
  for (std::size_t k = 0; k < field.rows.size(); ++k) {
    const PolylinePath path(field.rows[k].polyline);
    const auto arcs = vine_arcs(path.length(), c.plant_spacing);
    for (std::size_t i = 0; i < arcs.size(); ++i) {
      const bool dropped = drop(rng);  // drawn for every vine: stable sequence
      if (missing[k][i] || dropped) continue;
      field.plants.push_back({path.point(arcs[i]), 0.5 * c.trunk_diameter, c.canopy_top,
                              static_cast<int>(k), PlantKind::vine});
    }
    const auto posts = post_arcs(path.length(), c.post_spacing);
    // Posts stand 0.15 m over a clumps canopy; a trimmed solid hedge hides them as far below its
    // top (issue 10: no trellis shows on a real hedge mesh), only the end posts stand out.
    const double post_top = c.canopy_shape == CanopyShape::solid_hedge ? -0.15 : 0.15;
    for (std::size_t j = 0; j < posts.size(); ++j) {
      const bool end = j == 0 || j + 1 == posts.size();
      field.plants.push_back({path.point(posts[j]),
                              0.5 * (end ? c.end_post_diameter : c.post_diameter),
                              c.canopy_top + (end ? 0.2 : post_top), static_cast<int>(k),
                              end ? PlantKind::end_post : PlantKind::post});
    }
  }
}

void build_vine_geometry(Field& field, const VineyardConfig& c, std::mt19937_64& rng, bool vines) {
  std::vector<PolylinePath> paths;
  for (const auto& row : field.rows) paths.emplace_back(row.polyline);
  for (auto& p : field.plants) {
    const double z0 = field.terrain.height(p.position.x(), p.position.y());
    const Eigen::Vector3d base(p.position.x(), p.position.y(), z0);
    if (p.kind == PlantKind::vine && vines) {
      const Eigen::Vector2d t =
          p.row >= 0 ? paths[static_cast<std::size_t>(p.row)].tangent(
                           paths[static_cast<std::size_t>(p.row)].project(p.position))
                     : Eigen::Vector2d::UnitX();
      p.height = add_vine(field.mesh, base, t, c, rng);
    } else if (p.kind == PlantKind::post || p.kind == PlantKind::end_post) {
      const Eigen::Vector3f b = base.cast<float>() - Eigen::Vector3f(0, 0, 0.05f);
      add_cylinder(field.mesh, b, b + Eigen::Vector3f(0, 0, static_cast<float>(p.height + 0.05)),
                   static_cast<float>(p.radius), 8, SurfaceClass::post, true);
    }
  }
  if (!c.wires || c.wire_count <= 0) return;
  const double lo = c.cordon_height_max, hi = std::max(lo, c.canopy_top - 0.15);
  for (const auto& path : paths) {
    const auto arcs = post_arcs(path.length(), c.post_spacing);
    for (int w = 0; w < c.wire_count; ++w) {
      const double h = c.wire_count == 1 ? lo : lo + (hi - lo) * w / (c.wire_count - 1);
      for (std::size_t j = 0; j + 1 < arcs.size(); ++j) {
        // Short pieces: a 5 m sliver triangle has a bounding box that overlaps everything along
        // the row and slows every ray (measured: ~8 % of an OS1-64 sweep, bench/sim_drive_bench).
        const int pieces = std::max(1, static_cast<int>(std::ceil((arcs[j + 1] - arcs[j]) / kWirePiece)));
        for (int k = 0; k < pieces; ++k) {
          const double s0 = arcs[j] + (arcs[j + 1] - arcs[j]) * k / pieces;
          const double s1 = arcs[j] + (arcs[j + 1] - arcs[j]) * (k + 1) / pieces;
          add_cylinder(field.mesh, ground_point(field.terrain, path.point(s0), h),
                       ground_point(field.terrain, path.point(s1), h),
                       static_cast<float>(0.5 * c.wire_diameter), 4, SurfaceClass::wire);
        }
      }
    }
  }
}

void scatter_weeds(Field& field, WeedLevel level, double corridor_width, std::mt19937_64& rng) {
  scatter_weeds(field, level, corridor_width, WeedSize{}, rng);
}

void scatter_weeds(Field& field, WeedLevel level, double corridor_width, const WeedSize& size,
                   std::mt19937_64& rng) {
  if (level == WeedLevel::none || corridor_width <= 0.05) return;
  const double margin = std::min(0.25, 0.25 * corridor_width);  // [m] kept clear beside the rows
  const bool many = level == WeedLevel::many;
  const double density = many ? 2.0 : 0.4;      // [1/m^2]
  const double max_height = size.max_height > 0.0 ? size.max_height : many ? 0.5 : 0.25;  // [m]
  const double min_radius = 0.05;                                                      // [m]
  const double max_radius = size.max_radius > 0.0 ? std::max(size.max_radius, min_radius)
                                                  : min_radius + (many ? 0.2 : 0.1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t k = 0; k + 1 < field.rows.size(); ++k) {
    if (field.rows[k].block != field.rows[k + 1].block) continue;
    const PolylinePath path(field.rows[k].polyline);
    std::poisson_distribution<int> count(density * path.length() * (corridor_width - 2.0 * margin));
    const int n = count(rng);
    for (int i = 0; i < n; ++i) {
      const double s = u(rng) * path.length();
      const double off = margin + u(rng) * (corridor_width - 2.0 * margin);
      const Eigen::Vector2d p = path.point(s) + off * path.left(s);
      const double h = 0.04 + u(rng) * (std::max(max_height, 0.04) - 0.04);
      const double r = min_radius + u(rng) * (max_radius - min_radius);
      field.plants.push_back({p, r, h, -1, PlantKind::weed});
      add_blob(field.mesh, ground_point(field.terrain, p, 0.5 * h),
               Eigen::Vector3f(static_cast<float>(r), static_cast<float>(r),
                               static_cast<float>(0.5 * h)),
               0.3f, rng, SurfaceClass::weed, true);
    }
  }
}

void add_ground(Field& field, std::size_t max_triangles) {
  Eigen::AlignedBox2d box = field.row_bounds();
  if (box.isEmpty()) return;
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(field.headland_width);
  const Eigen::Vector2d lo = box.min() - margin, hi = box.max() + margin;
  TerrainConfig tc = field.terrain.config();
  const double area = (hi - lo).prod();
  const double cell = std::sqrt(2.0 * area / static_cast<double>(max_triangles));
  if (cell <= tc.cell_size) {
    field.mesh.append(field.terrain.mesh(lo, hi));
    return;
  }
  tc.cell_size = cell;  // same seed and shape, coarser cells
  field.mesh.append(Terrain(tc).mesh(lo, hi));
}

int instance_along_rows(Field& field, const TriangleMesh& instance, double spacing) {
  int placed = 0;
  for (const auto& row : field.rows) {
    const PolylinePath path(row.polyline);
    for (double s = 0.0; s + 0.5 * spacing <= path.length(); s += spacing) {
      const Eigen::Vector2d t = path.tangent(std::min(s + 0.5 * spacing, path.length()));
      const Eigen::Vector2d p = path.point(s);
      Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
      T.linear().col(0) = Eigen::Vector3f(static_cast<float>(t.y()), static_cast<float>(-t.x()), 0);
      T.linear().col(1) = Eigen::Vector3f(static_cast<float>(t.x()), static_cast<float>(t.y()), 0);
      T.linear().col(2) = Eigen::Vector3f::UnitZ();
      T.translation() = ground_point(field.terrain, p);
      field.mesh.append(instance, T);
      ++placed;
    }
  }
  return placed;
}

}  // namespace rownav::sim
