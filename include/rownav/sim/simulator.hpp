#pragma once
/// @file simulator.hpp The closed simulation loop: robot dynamics, LiDAR, proprioception and
/// ground truth at their own rates. A scripted driver or the navigation stack supplies commands.
#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"
#include "rownav/core/scan2d.hpp"
#include "rownav/core/sensor_samples.hpp"
#include "rownav/core/twist.hpp"
#include "rownav/sim/fault_config.hpp"
#include "rownav/sim/faults.hpp"
#include "rownav/sim/field.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/ground_contact.hpp"
#include "rownav/sim/ground_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/lidar_presets.hpp"
#include "rownav/sim/proprioception.hpp"
#include "rownav/sim/ray_caster.hpp"
#include "rownav/sim/robot.hpp"
#include "rownav/sim/sim_sink.hpp"

namespace rownav::sim {

/// Sensor suite and loop rates of a simulation.
struct SimConfig {
  LidarConfig lidar = lidar_preset("os1_16");  ///< LiDAR model (rate, FOV, noise, mount)
  EncoderConfig encoders;                      ///< wheel encoders
  ImuConfig imu;                               ///< IMU
  GnssConfig gnss;                 ///< GNSS (disabled by default: rownav is map-free and RTK-free)
  double physics_rate_hz = 100.0;  ///< [Hz] robot integration rate
  double ground_truth_rate_hz = 20.0;  ///< [Hz] ground-truth samples emitted
  double truth_reach = 10.0;           ///< [m] rows within this distance are listed in the truth
  std::uint64_t seed = 1;              ///< seeds every noise source
  FaultsConfig faults;  ///< injected sensor faults and a walking person (default: none)
  GroundContactConfig ground_contact;  ///< how the base rests on the terrain (z, roll, pitch)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("lidar", s.lidar);
    v("encoders", s.encoders);
    v("imu", s.imu);
    v("gnss", s.gnss);
    v("physics_rate_hz", s.physics_rate_hz);
    v("ground_truth_rate_hz", s.ground_truth_rate_hz);
    v("truth_reach", s.truth_reach);
    v("seed", s.seed);
    v("faults", s.faults);
    v("ground_contact", s.ground_contact);
  }
  void validate() const;
};

/// Steps a robot through a field. Construction builds the Embree scene (may throw on bad
/// configs); step() never throws.
class Simulator {
 public:
  Simulator(const Field& field, const RobotConfig& robot, const SimConfig& config,
            const core::Pose2& start);

  /// Applies `cmd` for one physics step (1 / physics_rate_hz) and emits the sensor data that
  /// falls due in that step.
  void step(const core::Twist2& cmd, SimSink& sink);

  double time() const { return robot_.state().stamp; }
  double dt() const { return dt_; }
  const RobotState& robot_state() const { return robot_.state(); }
  const Robot& robot() const { return robot_; }
  const Field& field() const { return field_; }
  /// Ground truth of the last step.
  const GroundTruth& ground_truth() const { return truth_now_; }
  /// Indices into the field's plants, in the order the footprint crushed them.
  const std::vector<int>& crushed_plants() const { return crush_.crushed_indices(); }
  const FieldTruth& field_truth() const { return truth_; }
  const RayCaster& world() const { return caster_; }
  const Lidar& lidar() const { return lidar_; }
  const SimConfig& config() const { return config_; }
  /// The walking person of the faults (on the terrain) at time t; nullopt without one.
  std::optional<ObstacleBox> person_at(double t) const;
  /// T_world_base in 3D (terrain height, roll and pitch; see rest_on_ground) for a planar pose.
  Eigen::Isometry3d pose3d(const core::Pose2& T_world_base) const;
  /// Carries the robot by `delta_base` (x forward, y left, theta: its base frame now) over the
  /// next steps, at `speed` [m/s] along the straight line and `yaw_rate` [rad/s], whatever it is
  /// commanded, without its wheels turning: a person pushing it, a tow, a hand (issue 15: the ROS
  /// sim node's ~carry). The LiDAR sees the move, the encoders and the IMU do not. A call
  /// replaces a carry still under way. The slower of the line and the turn sets the pace; a speed
  /// (yaw_rate) <= 0 or not finite sets none for the line (the turn): with neither, at once.
  void carry(const core::Pose2& delta_base, double speed, double yaw_rate);
  /// A carry is still under way.
  bool carrying() const { return carry_.has_value(); }

 private:
  void emit_lidar(SimSink& sink);
  void emit_proprioception(SimSink& sink);
  Eigen::Isometry3d pose_at(double t) const;
  void update_truth();
  void update_person(double t);
  void step_carry();

  const Field& field_;
  SimConfig config_;
  double dt_;
  Robot robot_;
  RayCaster caster_;
  Lidar lidar_;
  FieldTruth truth_;
  CrushCounter crush_;
  WheelEncoders encoders_;
  Imu imu_;
  Gnss gnss_;
  FaultInjector faults_;
  GroundTruth truth_now_;
  std::deque<std::pair<double, Eigen::Isometry3d>> history_;  // recent T_world_base for sweeps
  // Samples emitted so far per stream; due times are n / rate, so stamps do not drift.
  std::int64_t n_sweeps_ = 0, n_encoders_ = 0, n_imu_ = 0, n_gnss_ = 0, n_truth_ = 0;
  std::int64_t n_steps_ = 0;
  /// What is left of a carry, in the world frame (Simulator::carry).
  struct Carry {
    Eigen::Vector2d remaining;  ///< [m]
    double turn = 0.0;          ///< [rad]
    double speed = 0.0;         ///< [m/s]
    double yaw_rate = 0.0;      ///< [rad/s]
  };
  std::optional<Carry> carry_;
  core::Twist2 last_twist_;
};

}  // namespace rownav::sim
