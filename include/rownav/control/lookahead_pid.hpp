#pragma once
/// @file lookahead_pid.hpp PID steering towards a point ahead on the path, speed reduced by the
/// front obstacle (Bertoglio 2023, 003_25dc0df51a1e5faf.txt sec. II-B: "We use a PID controller
/// to steer toward the point on this line that is 1 m in front of the robot. The linear speed is
/// set to a constant value, and it is reduced if an object in front of the robot is detected.").
#include <string_view>

#include "rownav/control/controller.hpp"
#include "rownav/control/front_obstacle.hpp"
#include "rownav/control/pid.hpp"
#include "rownav/core/config_fields.hpp"

namespace rownav::control {

/// Parameters of LookaheadPidController.
struct LookaheadPidConfig {
  double lookahead =
      1.0;  ///< [m] distance of the target point along the path (Bertoglio sec. II-B)
  /// PID on the bearing [rad] of the target point -> omega [rad/s] (gains not given by the paper;
  /// rownav: damping ~0.85 with a 1 m lookahead at 0.5 m/s)
  PidGains pid{1.5, 0.05, 0.05, 0.5};
  SlowdownConfig slowdown;  ///< speed reduced by the obstacle distance (Bertoglio sec. II-B)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("lookahead", s.lookahead);
    v("pid", s.pid);
    v("slowdown", s.slowdown);
  }
  void validate() const;
};

/// Lookahead PID path follower; state: the PID integrator and previous bearing.
class LookaheadPidController : public PathController {
 public:
  using Config = LookaheadPidConfig;
  explicit LookaheadPidController(const LookaheadPidConfig& config = {});
  std::string_view name() const override { return "lookahead_pid"; }
  core::Twist2 compute(const ControlInput& in) override;
  void reset() override { pid_.reset(); }
  const LookaheadPidConfig& config() const { return config_; }

 private:
  LookaheadPidConfig config_;
  Pid pid_;
};

}  // namespace rownav::control
