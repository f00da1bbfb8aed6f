#pragma once
// Simulated fields like Emmi 2021's data sets (002_806e72d300173f73.txt, Table 2, Fig. 11), for
// the map-stage tools: B1 (market-garden beds, 4 lanes x 50 m, 1 m lanes; cabbage plants) and
// V1 (vineyard, 5 lanes x 140 m, 2.5 m lanes), with some inter-row weeds. Flat ground: the
// paper neglects the slope.
#include <string>

#include "rownav/sim/field_config.hpp"

namespace rownav::bench_map {

struct MapField {
  std::string name;
  sim::FieldConfig config;
  double scanner_height = 0.2;  // [m] planar scanner height above the ground (hits the crop)
  double dbscan_eps = 0.35;     // [m] row clustering radius (vines are 1 m apart: larger)
};

inline MapField field_b1(std::uint64_t seed) {
  MapField f;
  f.name = "B1";
  f.config.kind = sim::FieldKind::row_crop;
  f.config.name = "b1";
  f.config.row_crop.crop = sim::CropType::cabbage;
  f.config.row_crop.rows = 5;  // 4 lanes
  f.config.row_crop.row_length = 50.0;
  f.config.row_crop.row_spacing = 1.0;
  f.config.row_crop.headland_width = 4.0;
  f.config.row_crop.weeds = sim::WeedLevel::some;  // weed hits: what false positives turn into crop
  f.config.terrain.roughness = 0.0;
  f.config.seed = seed;
  f.scanner_height = 0.15;
  f.dbscan_eps = 0.35;
  return f;
}

inline MapField field_v1(std::uint64_t seed) {
  MapField f;
  f.name = "V1";
  f.config.kind = sim::FieldKind::vineyard;
  f.config.name = "v1";
  f.config.vineyard.rows = 6;  // 5 lanes
  f.config.vineyard.row_length = 140.0;
  f.config.vineyard.row_spacing = 2.5;
  f.config.vineyard.headland_width = 6.0;
  f.config.vineyard.weeds = sim::WeedLevel::some;
  f.config.terrain.roughness = 0.0;
  f.config.seed = seed;
  f.scanner_height = 0.25;  // trunks and posts, below the cordon (the paper's trunk detector)
  f.dbscan_eps = 1.2;
  return f;
}

}  // namespace rownav::bench_map
