// The standard simulated scenarios of the detection accuracy benchmark and their frames.
#include <random>

#include "rownav/core/angle.hpp"
#include "rownav/io/detection_eval.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/simulator.hpp"

namespace rownav::io {

namespace {

EvalScenario vineyard(const std::string& name, double spacing, sim::GrowthStage stage,
                      sim::WeedLevel weeds, const std::string& lidar, std::uint64_t seed) {
  EvalScenario s;
  s.name = name;
  s.field.kind = sim::FieldKind::vineyard;
  s.field.name = name;
  s.field.seed = seed;
  s.field.vineyard.rows = 6;
  s.field.vineyard.row_length = 40.0;
  s.field.vineyard.row_spacing = spacing;
  s.field.vineyard.stage = stage;
  s.field.vineyard.weeds = weeds;
  s.lidar_preset = lidar;
  s.seed = seed;
  s.crop = "vineyard";
  return s;
}

}  // namespace

std::vector<EvalScenario> standard_scenarios(bool quick) {
  using G = sim::GrowthStage;
  using W = sim::WeedLevel;
  std::vector<EvalScenario> out = {
      vineyard("vine_narrow_low_clean", 1.8, G::low, W::none, "os1_16", 11),
      vineyard("vine_narrow_medium_weeds", 1.8, G::medium, W::some, "os1_16", 12),
      vineyard("vine_narrow_high_weedy", 1.8, G::high, W::many, "os1_64", 13),
      vineyard("vine_wide_low_weeds", 2.8, G::low, W::some, "os1_16", 14),
      vineyard("vine_wide_medium_clean", 2.8, G::medium, W::none, "os1_64", 15),
      vineyard("vine_wide_high_weedy", 2.8, G::high, W::many, "os1_16", 16),
      vineyard("vine_narrow_2d", 1.8, G::medium, W::some, "lms_1081", 17),
  };
  EvalScenario missing = vineyard("vine_missing_plants", 1.8, G::medium, W::some, "os1_16", 18);
  missing.field.vineyard.missing_plants_percent = 25.0;
  missing.field.vineyard.gap_count = 6;
  missing.field.vineyard.gap_length_plants = 4;
  out.push_back(missing);

  EvalScenario orchard;
  orchard.name = "orchard";
  orchard.field.kind = sim::FieldKind::orchard;
  orchard.field.name = "orchard";
  orchard.field.seed = 19;
  orchard.field.orchard.rows = 5;
  orchard.lidar_preset = "os1_16";
  orchard.seed = 19;
  orchard.max_lateral = 0.5;
  orchard.crop = "orchard";
  out.push_back(orchard);

  for (const auto& [name, lidar] :
       {std::pair{"maize_3d", "os1_16"}, std::pair{"maize_2d", "lms_1081"}}) {
    EvalScenario m;
    m.name = name;
    m.field.kind = sim::FieldKind::row_crop;
    m.field.name = name;
    m.field.seed = 20;
    m.field.row_crop.rows = 8;
    m.field.row_crop.row_length = 30.0;
    m.field.row_crop.weeds = sim::WeedLevel::some;
    m.lidar_preset = lidar;
    m.seed = 20;
    m.max_lateral = 0.1;  // 0.75 m rows: the wheels stay in the corridor
    m.crop = "row_crop";
    // The 2D scanner sits low under the maize canopy (TerraSentia-like, as the corn data set).
    if (std::string(lidar) == "lms_1081") m.mount_xyz = Eigen::Vector3d(0.3, 0.0, 0.3);
    out.push_back(m);
  }
  for (auto& s : out) s.frames = quick ? 6 : 40;
  return out;
}

SimulatedFrames simulate_frames(const EvalScenario& s) {
  const sim::Field field = sim::generate_field(s.field);
  sim::SimConfig config;
  config.lidar = sim::lidar_preset(s.lidar_preset);
  if (s.mount_xyz) config.lidar.mount_xyz = *s.mount_xyz;
  config.seed = s.seed;
  const sim::Simulator simulator(field, sim::RobotConfig{}, config, core::Pose2{});
  const sim::FieldTruth& truth = simulator.field_truth();
  sim::Lidar lidar(config.lidar, s.seed);
  SimulatedFrames out;
  out.T_base_lidar = config.lidar.T_base_lidar();
  const auto blocks = truth.blocks();
  if (blocks.empty() || truth.corridor_count(blocks.front()) == 0)
    throw std::invalid_argument(s.name + ": field has no corridor");
  const int block = blocks.front();
  std::mt19937_64 rng(s.seed);
  std::uniform_int_distribution<int> corridor(0, truth.corridor_count(block) - 1);
  std::uniform_real_distribution<double> along(0.15, 0.85), unit(-1.0, 1.0);
  for (int i = 0; i < s.frames; ++i) {
    const auto& c = truth.corridor_centre(block, corridor(rng));
    const auto k = std::min(c.size() - 2, static_cast<std::size_t>(along(rng) * (c.size() - 1)));
    const Eigen::Vector2d d = (c[k + 1] - c[k]).normalized();
    const Eigen::Vector2d p = c[k] + unit(rng) * s.max_lateral * Eigen::Vector2d(-d.y(), d.x());
    const core::Pose2 pose(p.x(), p.y(),
                           std::atan2(d.y(), d.x()) + core::deg2rad(s.max_heading_deg) * unit(rng));
    const Eigen::Isometry3d T_world_base = simulator.pose3d(pose);
    const sim::PoseAt pose_at = [&](double) { return T_world_base; };
    const double stamp = 0.1 * i;
    EvalFrame f;
    f.planar = config.lidar.kind == sim::LidarKind::planar;
    if (f.planar)
      f.scan = lidar.scan(simulator.world(), pose_at, stamp);
    else
      f.cloud = lidar.sweep(simulator.world(), pose_at, stamp);
    f.truth = truth.at(pose, stamp, config.truth_reach);
    out.frames.push_back(std::move(f));
  }
  return out;
}

}  // namespace rownav::io
