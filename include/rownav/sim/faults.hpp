#pragma once
/// @file faults.hpp The simulator's fault injector (issue 13): a SimSink decorator between the
/// simulated sensors and the sink that corrupts, drops, delays, repeats or re-stamps what passes
/// through according to FaultsConfig (sim/fault_config.hpp), and the walking person, an
/// ObstacleBox the LiDAR ray-casts. Owned by the Simulator; deterministic per seed; never
/// throws after construction.
#include <cstdint>
#include <deque>
#include <optional>
#include <random>
#include <variant>
#include <vector>

#include "rownav/core/pose2.hpp"
#include "rownav/sim/fault_config.hpp"
#include "rownav/sim/obstacle_box.hpp"
#include "rownav/sim/sim_sink.hpp"

namespace rownav::sim {

/// Applies the configured faults to the samples of one simulator; forwards to the sink bound
/// by begin_step().
class FaultInjector : public SimSink {
 public:
  /// Validates `config` (std::invalid_argument naming the field).
  FaultInjector(const FaultsConfig& config, std::uint64_t seed);

  /// Binds the sink of this step at simulated time `t` (samples are judged by the time they are
  /// emitted) and delivers the frames held back (jitter) that are due by then. `robot` is the
  /// robot's true pose, from which the person sets off at its start.
  void begin_step(double t, const core::Pose2& robot, SimSink& out);

  void on_cloud(const core::PointCloud& c, const std::vector<SurfaceClass>& labels) override;
  void on_scan(const core::Scan2D& s, const std::vector<SurfaceClass>& labels) override;
  void on_encoders(const core::WheelEncoderSample& s) override;
  void on_imu(const core::ImuSample& s) override;
  void on_gnss(const core::GnssFix& s) override;
  void on_ground_truth(const GroundTruth& g) override;

  /// The person's box at time t (ground z 0: the simulator sets it on the terrain); nullopt
  /// before the person appears or without one.
  std::optional<ObstacleBox> person_at(double t) const;
  const FaultsConfig& config() const { return config_; }

 private:
  struct Frame {
    std::variant<core::PointCloud, core::Scan2D> data;
    std::vector<SurfaceClass> labels;
    double release = 0.0;  // [s] when a held frame is delivered
  };
  struct PersonPath {
    Eigen::Vector2d from, centre, dir;  // [m] start, on the robot's line; unit walking direction
    double yaw = 0.0;
  };
  void lidar_frame(Frame f);
  void corrupt(Frame& f);
  void restamp(Frame& f);
  void repeat(Frame f);
  void deliver(Frame f);
  void forward(const Frame& f);

  FaultsConfig config_;
  std::mt19937_64 rng_;
  SimSink* out_ = nullptr;
  double now_ = 0.0;
  std::int64_t rate_count_ = 0;
  std::optional<double> stall_stamp_;
  std::optional<Frame> swapped_;    // out_of_order: the frame held until the next one
  std::deque<Frame> held_;          // jitter: frames delayed, in order
  double last_release_ = -1e300;
  // Encoders: the counts reported, as the true increments scaled by the fault (exact integers
  // while no fault acts: doubles hold integers up to 2^53).
  std::optional<core::WheelEncoderSample> last_true_;
  double left_ = 0.0, right_ = 0.0;
  std::optional<PersonPath> person_;
};

}  // namespace rownav::sim
