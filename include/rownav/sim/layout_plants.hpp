#pragma once
/// @file layout_plants.hpp Geometry of the trees and crop plants an imported layout lists, each
/// with its own sizes (PlantShape) or the field config's (issue 10: plants on layouts).
#include <random>
#include <vector>

#include "rownav/sim/field.hpp"
#include "rownav/sim/orchard.hpp"
#include "rownav/sim/row_crop.hpp"

namespace rownav::sim {

/// Applies the sizes of `shapes` (one per field.plants entry, or empty) to the plants' footprints
/// (posts: width = diameter, height; crops: width, height) before any geometry is built.
void apply_plant_shapes(Field& field, const std::vector<PlantShape>& shapes);

/// Builds every tree of field.plants with add_tree (trunk and crown from its PlantShape, else
/// from `orchard`) and every crop plant with add_crop_plant (`row_crop`'s crop and preset sizes
/// unless given), on field.terrain. Sets each plant's height to its top, a tree's radius to its
/// trunk radius, and the half width / height of every row holding trees to its crowns'.
void build_layout_plants(Field& field, const std::vector<PlantShape>& shapes,
                         const OrchardConfig& orchard, const RowCropConfig& row_crop,
                         std::mt19937_64& rng);

}  // namespace rownav::sim
