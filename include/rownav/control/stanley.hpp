#pragma once
/// @file stanley.hpp The Stanley steering law (Lan 2021, 001_b5f4b55a1b95775a.txt sec. 2.2,
/// eq. 15-21): delta = theta_e + arctan(k e / v), which makes the cross-track error decay as
/// e(0) exp(-k t) (eq. 20-21).
///
/// The steering angle becomes a yaw rate: car-like robots (wheelbase > 0) use the bicycle model
/// omega = v tan(delta) / wheelbase; robots that turn in place use omega = g delta with
/// g = max(yaw_gain, yaw_gain_per_speed |v|) (the heading is driven to the Stanley steering
/// direction with time constant 1 / g; above 0.8 m/s g grows with speed as the bicycle model's
/// v / wheelbase does).
#include <string_view>

#include "rownav/control/controller.hpp"
#include "rownav/control/front_obstacle.hpp"
#include "rownav/core/config_fields.hpp"

namespace rownav::control {

/// Parameters of StanleyController.
struct StanleyConfig {
  double k = 1.0;  ///< [1/s] cross-track gain; the error decays as exp(-k t) (Lan 2021 eq. 20-21)
  /// [m/s] added to v in arctan(k e / v) so the law stays defined at low speed (Hoffmann 2007
  /// softening; Lan 2021 eq. 16 divides by v)
  double softening_speed = 0.1;
  double yaw_gain = 2.0;  ///< [1/s] omega = yaw_gain delta when wheelbase = 0 (rownav)
  /// [1/m] ... and at least yaw_gain_per_speed |v| delta: a heading loop that closes in the same
  /// distance, not the same time, at any speed, as the bicycle model's v tan(delta) / wheelbase.
  /// Track slip turns the robot by a yaw rate that grows with its speed; a fixed yaw_gain let it
  /// weave 0.05 m (mean) at 2 m/s in Bertoglio 2023's protocol, 0.004 m without the slip
  /// (issue 11). 2.5 = yaw_gain / 0.8 m/s: unchanged up to rownav's 0.8 m/s row speed (rownav)
  double yaw_gain_per_speed = 2.5;
  double wheelbase = 0.0;  ///< [m] > 0: bicycle model, omega = v tan(delta) / wheelbase
  /// [m] x of the control point (the front axle, Lan 2021 sec. 2.2) ahead of the base origin
  double front_axle_x = 0.0;
  double max_steer_deg = 35.0;  ///< [deg] |delta| limit (steering stop; degrees in configs)
  SlowdownConfig slowdown;      ///< speed reduction with the front obstacle distance (rownav)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("k", s.k);
    v("softening_speed", s.softening_speed);
    v("yaw_gain", s.yaw_gain);
    v("yaw_gain_per_speed", s.yaw_gain_per_speed);
    v("wheelbase", s.wheelbase);
    v("front_axle_x", s.front_axle_x);
    v("max_steer_deg", s.max_steer_deg);
    v("slowdown", s.slowdown);
  }
  void validate() const;
};

/// Stanley path follower. Stateless apart from its config.
class StanleyController : public PathController {
 public:
  using Config = StanleyConfig;
  explicit StanleyController(const StanleyConfig& config = {});
  std::string_view name() const override { return "stanley"; }
  core::Twist2 compute(const ControlInput& in) override;
  void reset() override {}
  const StanleyConfig& config() const { return config_; }

 private:
  StanleyConfig config_;
};

}  // namespace rownav::control
