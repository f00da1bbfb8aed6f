#pragma once
/// @file fir_pid.hpp FIR-filtered lateral error fed to a PID, with the steep-model safety
/// (Malavazi 2018, 004_1bee156ef8a2b3f7.txt sec. 2.3.3-2.3.5).
///
/// - Pre-control (sec. 2.3.3): the error is the distance to the target (corridor centre). When the
///   followed models are too steep (|tan| > steep_threshold, the robot turned within the row) the
///   error is computed where the robot's heading meets the models instead: rownav takes the
///   lateral offset of the point `steep_preview` ahead along the robot heading, e + L sin(theta_e),
///   which stays non-zero for a centred but turned robot (the case of the paper's Fig. 7), and
///   slows down and bounds omega.
/// - FIR (sec. 2.3.4, eq. 6): e_f[k] = b_0 e[k] + ... + b_N e[k-N].
/// - PID (sec. 2.3.5) on e_f; the output is the yaw-rate correction.
#include <deque>
#include <string_view>
#include <vector>

#include "rownav/control/controller.hpp"
#include "rownav/control/front_obstacle.hpp"
#include "rownav/control/pid.hpp"
#include "rownav/core/config_fields.hpp"

namespace rownav::control {

/// Parameters of FirPidController. The paper's FIR and PID values were "empirically tuned" and
/// are not given; these are rownav's.
struct FirPidConfig {
  /// [-] FIR impulse response b_0..b_N (Malavazi 2018 eq. 6); normalised to sum 1 if they do not
  std::vector<double> fir = {0.4, 0.3, 0.2, 0.1};
  /// PID on the filtered lateral error [m] -> omega [rad/s] (rownav: damping ~0.9 at 0.5 m/s)
  PidGains pid{2.0, 0.05, 3.6, 0.2};
  double steep_threshold = 0.3;    ///< [-] |tan| of the models beyond which they are steep
  double steep_preview = 1.0;      ///< [m] look-ahead of the steep-mode error (rownav)
  double steep_speed_scale = 0.5;  ///< [-] speed factor while the models are steep
  double steep_max_omega = 0.5;    ///< [rad/s] |omega| bound while the models are steep
  SlowdownConfig slowdown;         ///< speed reduction with the front obstacle distance (rownav)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("fir", s.fir);
    v("pid", s.pid);
    v("steep_threshold", s.steep_threshold);
    v("steep_preview", s.steep_preview);
    v("steep_speed_scale", s.steep_speed_scale);
    v("steep_max_omega", s.steep_max_omega);
    v("slowdown", s.slowdown);
  }
  void validate() const;
};

/// FIR + PID path follower; state: the FIR taps and the PID.
class FirPidController : public PathController {
 public:
  using Config = FirPidConfig;
  explicit FirPidController(const FirPidConfig& config = {});
  std::string_view name() const override { return "fir_pid"; }
  core::Twist2 compute(const ControlInput& in) override;
  void reset() override;
  const FirPidConfig& config() const { return config_; }

 private:
  double filter(double error);

  FirPidConfig config_;
  std::vector<double> b_;    // normalised FIR coefficients
  std::deque<double> taps_;  // e[k], e[k-1], ... (most recent first)
  Pid pid_;
};

}  // namespace rownav::control
