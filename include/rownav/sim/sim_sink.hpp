#pragma once
/// @file sim_sink.hpp What receives the simulator's output (sim/simulator.hpp); its own header
/// so that sink decorators (sim/faults.hpp) need not include the simulator.
#include <vector>

#include "rownav/core/point_cloud.hpp"
#include "rownav/core/scan2d.hpp"
#include "rownav/core/sensor_samples.hpp"
#include "rownav/sim/ground_truth.hpp"
#include "rownav/sim/triangle_mesh.hpp"

namespace rownav::sim {

/// Receives what the simulator produces, in time order. Default implementations ignore data.
class SimSink {
 public:
  virtual ~SimSink() = default;
  /// A 3D sweep (spinning LiDAR), stamped at its start, emitted when the sweep ends.
  virtual void on_cloud(const core::PointCloud&, const std::vector<SurfaceClass>& /*labels*/) {}
  /// A planar scan (2D LiDAR).
  virtual void on_scan(const core::Scan2D&, const std::vector<SurfaceClass>& /*labels*/) {}
  virtual void on_encoders(const core::WheelEncoderSample&) {}
  virtual void on_imu(const core::ImuSample&) {}
  virtual void on_gnss(const core::GnssFix&) {}
  virtual void on_ground_truth(const GroundTruth&) {}
};

}  // namespace rownav::sim
