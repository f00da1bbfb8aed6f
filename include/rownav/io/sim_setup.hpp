#pragma once
/// @file sim_setup.hpp Reading simulation set-ups from YAML and recording a simulation.
///
/// A sensors file holds a `sim::SimConfig`; its `lidar` map may name a `preset` (os1_16, os1_64,
/// vlp16, sick_tim571, sick_lms111, lms_1081) whose values the other keys then override:
/// @code
/// lidar: {preset: os1_16, mount_xyz: [0.35, 0.0, 0.75], range_noise_std: 0.02}
/// imu: {rate_hz: 200}
/// seed: 7
/// @endcode
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>

#include "rownav/io/recording.hpp"
#include "rownav/sim/simulator.hpp"

namespace rownav::io {

/// Decodes a SimConfig node (strict; `lidar.preset` selects the LiDAR defaults).
sim::SimConfig decode_sim_config(const YAML::Node& node, const std::string& file);
/// Loads a sensors YAML file into a SimConfig. Throws InputError with file:line:col.
sim::SimConfig load_sim_config(const std::filesystem::path& file);

/// Forwards everything a Simulator emits to a RecordingWriter; `lidar_every` keeps one LiDAR
/// frame in N (recordings of dense 3D LiDARs are large: ~250 kB per OS1-16 sweep).
class RecordingSink : public sim::SimSink {
 public:
  explicit RecordingSink(RecordingWriter& writer, int lidar_every = 1)
      : writer_(writer), lidar_every_(lidar_every < 1 ? 1 : lidar_every) {}
  void on_cloud(const core::PointCloud& cloud, const std::vector<sim::SurfaceClass>&) override;
  void on_scan(const core::Scan2D& scan, const std::vector<sim::SurfaceClass>&) override;
  void on_encoders(const core::WheelEncoderSample& s) override { writer_.write_encoders(s); }
  void on_imu(const core::ImuSample& s) override { writer_.write_imu(s); }
  void on_gnss(const core::GnssFix& s) override { writer_.write_gnss(s); }
  void on_ground_truth(const sim::GroundTruth& g) override { writer_.write_ground_truth(g); }
  /// LiDAR frames produced and frames written.
  int frames_seen() const { return seen_; }
  int frames_written() const { return written_; }

 private:
  bool keep() { return (seen_++ % lidar_every_) == 0 && ++written_ > 0; }
  RecordingWriter& writer_;
  int lidar_every_;
  int seen_ = 0, written_ = 0;
};

}  // namespace rownav::io
