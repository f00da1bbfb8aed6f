// The walking person of the faults (sim/faults.hpp) in the simulator: ray-cast by the LiDAR as
// an `obstacle`, and the footprint's clearance to it in the ground truth.
#include <gtest/gtest.h>

#include <cmath>

#include "rownav/sim/field_config.hpp"
#include "rownav/sim/simulator.hpp"

namespace rownav::sim {
namespace {

struct Count : SimSink {
  int obstacle_points = 0, frames = 0;
  double first_seen = -1.0, min_clearance = 1e9;
  double now = 0.0;
  void on_cloud(const core::PointCloud&, const std::vector<SurfaceClass>& labels) override {
    ++frames;
    int n = 0;
    for (const auto l : labels) n += l == SurfaceClass::obstacle;
    if (n > 0 && first_seen < 0.0) first_seen = now;
    obstacle_points += n;
  }
  void on_ground_truth(const GroundTruth& g) override {
    min_clearance = std::min(min_clearance, g.obstacle_clearance);
  }
};

Field corridor_field() {
  FieldConfig c;
  c.kind = FieldKind::vineyard;
  c.vineyard.rows = 2;
  c.vineyard.row_length = 20.0;
  c.vineyard.row_spacing = 2.0;
  c.vineyard.gap_count = 0;
  c.seed = 3;
  return generate_field(c);
}

TEST(Person, IsSeenByTheLidarAndTouchedByADrivingRobot) {
  const Field field = corridor_field();
  SimConfig cfg;
  cfg.faults.person.enabled = true;
  cfg.faults.person.start = 1.0;
  cfg.faults.person.ahead = 4.0;
  cfg.faults.person.side = 1.0;
  // Drives along the corridor centre (y = 1) at 0.5 m/s into the person standing on its line.
  Simulator sim(field, RobotConfig{}, cfg, core::Pose2(2.0, 1.0, 0.0));
  Count count;
  for (int k = 0; k < 1000; ++k) {
    count.now = sim.time();
    sim.step({0.5, 0.0, 0.0}, count);
  }
  EXPECT_GT(count.obstacle_points, 1000);
  EXPECT_NEAR(count.first_seen, 1.1, 0.15);  // the sweep after it appears
  EXPECT_EQ(count.min_clearance, 0.0);       // the robot drove into it
  const auto box = sim.person_at(sim.time());
  ASSERT_TRUE(box);
  EXPECT_NEAR(box->base.y(), 1.0, 0.05);  // on the robot's line when it set off (it drifts)
  EXPECT_NEAR(box->base.z(), field.terrain.height(box->base.x(), box->base.y()), 1e-9);
}

TEST(Person, NoFaultsNoPersonNoClearance) {
  const Field field = corridor_field();
  Simulator sim(field, RobotConfig{}, SimConfig{}, core::Pose2(2.0, 1.0, 0.0));
  Count count;
  for (int k = 0; k < 300; ++k) sim.step({0.5, 0.0, 0.0}, count);
  EXPECT_EQ(count.obstacle_points, 0);
  EXPECT_FALSE(std::isfinite(count.min_clearance) && count.min_clearance < 1e9);
  EXPECT_FALSE(sim.person_at(3.0));
}

}  // namespace
}  // namespace rownav::sim
