#pragma once
/// @file row_dressing.hpp Dresses row polylines with plants, posts, wires, weeds and ground:
/// shared by the procedural generators and by imported layouts.
#include <random>
#include <string>
#include <vector>

#include "rownav/sim/field.hpp"
#include "rownav/sim/vineyard.hpp"

namespace rownav::sim {

/// An empty field of the given kind with its spacing, headland and terrain set (the part every
/// procedural generator starts from).
Field make_empty_field(std::string name, FieldKind kind, double row_spacing,
                       double headland_width, const TerrainConfig& terrain);

/// `count` parallel rows along +x from x = 0 to `length`, row k at y = k * spacing, all bent by
/// the same lateral sine y += amplitude * sin(2 pi x / wavelength + phase) (phase from `rng`),
/// sampled every <= 1 m. Fills id, block 0, polyline, half_width and height.
std::vector<Row> make_parallel_rows(int count, double length, double spacing, double amplitude,
                                    double wavelength, double half_width, double height,
                                    std::mt19937_64& rng);

/// [m] arc lengths of the posts of a row of length `length`: both ends and intermediate posts
/// evenly spaced as close as possible to `spacing`.
std::vector<double> post_arcs(double length, double spacing);

/// Places vines every plant_spacing along each row of `field` (first and last half a spacing
/// from the end posts), removes `gap_count` runs of `gap_length_plants` consecutive vines in
/// random rows and `missing_plants_percent` % of the rest at random, and adds the posts and
/// end posts. Appends to field.plants.
void place_vines(Field& field, const VineyardConfig& config, std::mt19937_64& rng);

/// Builds the mesh of every vine (unless `vines` is false, e.g. when a vine mesh is instanced
/// instead), post and end post in field.plants, and the wires along each row between its end
/// posts. Sets each vine's height to its canopy top.
void build_vine_geometry(Field& field, const VineyardConfig& config, std::mt19937_64& rng,
                         bool vines = true);

/// Scatters inter-row weed tufts (kind weed, row -1, plus coarse blobs labelled weed) over the
/// corridor on the left of each row that has a left neighbour in its block, `corridor_width`
/// wide. Densities: some = 0.4 / m^2 up to 0.25 m tall, many = 2 / m^2 up to 0.5 m.
void scatter_weeds(Field& field, WeedLevel level, double corridor_width, std::mt19937_64& rng);

/// Weed sizes overriding a level's preset (0 keeps the preset: some <= 0.25 m tall, many
/// <= 0.5 m; radius <= 0.15 / 0.25 m).
struct WeedSize {
  double max_height = 0.0;  ///< [m]
  double max_radius = 0.0;  ///< [m]
};
/// scatter_weeds with the sizes of `size`.
void scatter_weeds(Field& field, WeedLevel level, double corridor_width, const WeedSize& size,
                   std::mt19937_64& rng);

/// Appends the terrain mesh under the rows' bounds grown by field.headland_width on every side.
/// The cell is coarsened when needed to keep the ground under `max_triangles`.
void add_ground(Field& field, std::size_t max_triangles = 400000);

/// Instances `instance` along every row every `spacing` metres from its start. Instance frame:
/// x to the right of the row, y along it, z up, origin on the row line at ground level.
/// @return number of instances placed
int instance_along_rows(Field& field, const TriangleMesh& instance, double spacing);

}  // namespace rownav::sim
