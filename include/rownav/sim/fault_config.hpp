#pragma once
/// @file fault_config.hpp The `faults:` section of the simulator's sensors config (issue 13,
/// "faults in the simulator"): sensor faults injected between the simulated sensors and the
/// SimSink, and a person walking into the corridor. Every fault is off by default; each has its
/// own window [start, start + duration) of simulated time and its own magnitude. Seeded.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"

namespace rownav::sim {

/// When a fault acts: [start, start + duration) of simulated time, if enabled.
struct FaultWindow {
  bool enabled = false;   ///< off by default: no fault
  double start = 10.0;    ///< [s] simulated time the fault begins
  double duration = 1.0;  ///< [s] how long it lasts

  bool active(double t) const { return enabled && t >= start && t < start + duration; }
  double end() const { return start + duration; }
  template <class S, class V>
  static void window_fields(S& s, V& v) {
    v("enabled", s.enabled);
    v("start", s.start);
    v("duration", s.duration);
  }
  void validate_window() const {
    core::check_non_negative(start, "start");
    core::check(duration > 0.0 && duration <= 1e6, "duration", "must be in (0, 1e6] s");
  }
};

/// No LiDAR frame at all (a loose cable, a driver restart; issue 13: 0.2-3 s).
struct LidarDropoutFault : FaultWindow {
  template <class S, class V>
  static void fields(S& s, V& v) { window_fields(s, v); }
  void validate() const { validate_window(); }
};

/// A slow or irregular LiDAR: one frame in `keep_every` kept, each kept frame delivered late by
/// a uniform [0, jitter] delay (frames stay in order, as from a driver's queue).
struct LidarRateFault : FaultWindow {
  int keep_every = 3;   ///< [-] 1: every frame (10 Hz -> 3.3 Hz with 3)
  double jitter = 0.0;  ///< [s] largest extra delivery delay
  template <class S, class V>
  static void fields(S& s, V& v) {
    window_fields(s, v);
    v("keep_every", s.keep_every);
    v("jitter", s.jitter);
  }
  void validate() const {
    validate_window();
    core::check_range(keep_every, 1, 1000, "keep_every");
    core::check_range(jitter, 0.0, 10.0, "jitter");
  }
};

/// A burst of non-finite points (a corrupted driver buffer): a `fraction` of each cloud's
/// points (of a scan's ranges) becomes NaN, `inf_share` of those +-Inf instead.
struct CloudNanFault : FaultWindow {
  double fraction = 0.2;   ///< [-] of the points
  double inf_share = 0.5;  ///< [-] of the poisoned points that are Inf, not NaN
  template <class S, class V>
  static void fields(S& s, V& v) {
    window_fields(s, v);
    v("fraction", s.fraction);
    v("inf_share", s.inf_share);
  }
  void validate() const {
    validate_window();
    core::check_range(fraction, 0.0, 1.0, "fraction");
    core::check_range(inf_share, 0.0, 1.0, "inf_share");
  }
};

/// Points lost at random (dust, rain, a dirty window; issue 13: 30 %).
struct PointLossFault : FaultWindow {
  double fraction = 0.3;  ///< [-] of the points (of a scan's ranges: no return)
  template <class S, class V>
  static void fields(S& s, V& v) {
    window_fields(s, v);
    v("fraction", s.fraction);
  }
  void validate() const {
    validate_window();
    core::check_range(fraction, 0.0, 1.0, "fraction");
  }
};

/// How frames are repeated or reordered.
enum class RepeatMode : std::uint8_t {
  duplicate,    ///< every frame delivered twice
  out_of_order  ///< frames delivered in swapped pairs (n + 1 before n)
};

/// Frames delivered twice or out of order (a bridge or network re-sending).
struct FrameRepeatFault : FaultWindow {
  RepeatMode mode = RepeatMode::duplicate;
  template <class S, class V>
  static void fields(S& s, V& v) {
    window_fields(s, v);
    v("mode", s.mode);
  }
  void validate() const { validate_window(); }
};

/// LiDAR stamps jump back by `offset` during the window (a clock resynchronised).
struct LidarTimeBackwardsFault : FaultWindow {
  double offset = 1.0;  ///< [s] subtracted from the stamps
  template <class S, class V>
  static void fields(S& s, V& v) {
    window_fields(s, v);
    v("offset", s.offset);
  }
  void validate() const {
    validate_window();
    core::check_range(offset, 0.0, 1e6, "offset");
  }
};

/// Every frame of the window carries the stamp of its first frame (a stalled driver clock).
struct LidarStampStallFault : FaultWindow {
  template <class S, class V>
  static void fields(S& s, V& v) { window_fields(s, v); }
  void validate() const { validate_window(); }
};

/// Wheels slip: the encoders over-read by `factor` (issue 13: 30 % for 2 s).
struct OdometrySlipFault : FaultWindow {
  double factor = 1.3;  ///< [-] encoder increments multiplied by this
  OdometrySlipFault() { duration = 2.0; }
  template <class S, class V>
  static void fields(S& s, V& v) {
    window_fields(s, v);
    v("factor", s.factor);
  }
  void validate() const {
    validate_window();
    core::check_range(factor, 0.0, 10.0, "factor");
  }
};

/// How the encoders fail.
enum class EncoderFaultMode : std::uint8_t {
  freeze,  ///< counts stop (ticks lost); counting resumes from there after the window
  coarse   ///< counts reported in steps of coarse_ticks
};

/// Frozen or coarse encoder counts.
struct EncoderFault : FaultWindow {
  EncoderFaultMode mode = EncoderFaultMode::freeze;
  int coarse_ticks = 64;  ///< [ticks] reporting step in `coarse` mode (of 2048 / rev: 1/32 rev)
  template <class S, class V>
  static void fields(S& s, V& v) {
    window_fields(s, v);
    v("mode", s.mode);
    v("coarse_ticks", s.coarse_ticks);
  }
  void validate() const {
    validate_window();
    core::check_range(coarse_ticks, 1, 1000000, "coarse_ticks");
  }
};

/// A step in the gyro's z bias (temperature, a knock).
struct GyroBiasFault : FaultWindow {
  double bias_deg_s = 2.0;  ///< [deg/s] added to the yaw rate
  template <class S, class V>
  static void fields(S& s, V& v) {
    window_fields(s, v);
    v("bias_deg_s", s.bias_deg_s);
  }
  void validate() const {
    validate_window();
    core::check_range(bias_deg_s, -1000.0, 1000.0, "bias_deg_s");
  }
};

/// GNSS fixes jump by `offset` (multipath, a wrong RTK fix; issue 13: 5 m).
struct GnssJumpFault : FaultWindow {
  Eigen::Vector2d offset{5.0, 0.0};  ///< [m] east, north added to valid fixes
  template <class S, class V>
  static void fields(S& s, V& v) {
    window_fields(s, v);
    v("offset", s.offset);
  }
  void validate() const {
    validate_window();
    core::check(offset.allFinite() && offset.norm() <= 1e4, "offset", "must be finite, <= 10 km");
  }
};

/// A person (an upright box) who walks into the corridor in front of the robot at `start`:
/// appears `ahead` metres in front of the robot's true pose and `side` metres to its left (right
/// when negative), walks across at `speed` to the robot's line, stands there until start +
/// duration, then walks on out of the corridor. Ray-cast by the LiDAR; touching it is a
/// collision.
struct PersonFault : FaultWindow {
  double ahead = 5.0;                 ///< [m] in front of the base at `start`
  double side = 1.5;                  ///< [m] to the left of the robot's line (right: < 0)
  double speed = 1.0;                 ///< [m/s] walking speed
  Eigen::Vector3d size{0.5, 0.5, 1.7};  ///< [m] box (issue 13: ~0.5 x 0.5 x 1.7 m)
  PersonFault() { duration = 20.0; }
  template <class S, class V>
  static void fields(S& s, V& v) {
    window_fields(s, v);
    v("ahead", s.ahead);
    v("side", s.side);
    v("speed", s.speed);
    v("size", s.size);
  }
  void validate() const {
    validate_window();
    core::check_range(ahead, 0.0, 100.0, "ahead");
    core::check_range(side, -20.0, 20.0, "side");
    core::check_range(speed, 0.01, 10.0, "speed");
    core::check(size.allFinite() && size.minCoeff() > 0.0 && size.maxCoeff() <= 10.0, "size",
                "each in (0, 10] m");
  }
};

/// Every fault the simulator can inject (SimConfig::faults). Defaults: none.
struct FaultsConfig {
  std::uint64_t seed = 1;  ///< mixed with SimConfig::seed: random choices of the faults
  LidarDropoutFault lidar_dropout;
  LidarRateFault lidar_rate;
  CloudNanFault cloud_nan;
  PointLossFault point_loss;
  FrameRepeatFault frame_repeat;
  LidarTimeBackwardsFault lidar_time_backwards;
  LidarStampStallFault lidar_stamp_stall;
  OdometrySlipFault odometry_slip;
  EncoderFault encoder;
  GyroBiasFault gyro_bias;
  GnssJumpFault gnss_jump;
  PersonFault person;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("seed", s.seed);
    v("lidar_dropout", s.lidar_dropout);
    v("lidar_rate", s.lidar_rate);
    v("cloud_nan", s.cloud_nan);
    v("point_loss", s.point_loss);
    v("frame_repeat", s.frame_repeat);
    v("lidar_time_backwards", s.lidar_time_backwards);
    v("lidar_stamp_stall", s.lidar_stamp_stall);
    v("odometry_slip", s.odometry_slip);
    v("encoder", s.encoder);
    v("gyro_bias", s.gyro_bias);
    v("gnss_jump", s.gnss_jump);
    v("person", s.person);
  }
  void validate() const;
  /// Whether any fault is enabled.
  bool any() const;
};

}  // namespace rownav::sim

template <>
struct rownav::core::EnumNames<rownav::sim::RepeatMode> {
  using E = rownav::sim::RepeatMode;
  static constexpr std::array<std::pair<E, std::string_view>, 2> values{
      {{E::duplicate, "duplicate"}, {E::out_of_order, "out_of_order"}}};
};

template <>
struct rownav::core::EnumNames<rownav::sim::EncoderFaultMode> {
  using E = rownav::sim::EncoderFaultMode;
  static constexpr std::array<std::pair<E, std::string_view>, 2> values{
      {{E::freeze, "freeze"}, {E::coarse, "coarse"}}};
};
