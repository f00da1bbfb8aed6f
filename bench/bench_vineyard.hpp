#pragma once
// The benchmarks' standard scene: a 20-row x 100 m high-canopy vineyard (sim::generate_field),
// the robot in the middle of corridor 9, heading along it.
#include <cmath>
#include <memory>

#include "rownav/sim/field_config.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/ray_caster.hpp"

namespace rownav::bench {

struct BenchVineyard {
  sim::Field field;
  std::unique_ptr<sim::RayCaster> caster;
  sim::PoseAt pose;  ///< the robot's pose over the sweep (slowly along the corridor)
};

inline const BenchVineyard& bench_vineyard() {
  // Built in place (never moved): the ray caster refers to the field's mesh.
  static const BenchVineyard* const v = [] {
    sim::FieldConfig f;
    f.vineyard.rows = 20;
    f.vineyard.row_length = 100.0;
    f.vineyard.stage = sim::GrowthStage::high;
    auto* out = new BenchVineyard;  // lives as long as the benchmark process
    out->field = sim::generate_field(f);
    out->caster = std::make_unique<sim::RayCaster>(out->field.mesh);
    const auto centre = sim::FieldTruth(out->field).corridor_centre(0, 9);  // a copy: the truth is a temporary
    const Eigen::Vector2d a = centre[centre.size() / 2], b = centre[centre.size() / 2 + 1];
    const Eigen::Vector2d d = (b - a).normalized();
    const double z = out->field.terrain.height(a.x(), a.y());
    out->pose = [a, d, z](double t) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.linear() = Eigen::AngleAxisd(std::atan2(d.y(), d.x()), Eigen::Vector3d::UnitZ()).matrix();
      T.translation() = Eigen::Vector3d(a.x() + t * d.x(), a.y() + t * d.y(), z);
      return T;
    };
    return out;
  }();
  return *v;
}

}  // namespace rownav::bench
