#pragma once
/// @file pure_pursuit.hpp Classic pure pursuit (Coulter 1992): the arc through the base origin and
/// the path point at the lookahead distance, kappa = 2 y / L^2, omega = v kappa. Suits car-like
/// robots (the curvature is what they steer).
#include <string_view>

#include "rownav/control/controller.hpp"
#include "rownav/control/front_obstacle.hpp"
#include "rownav/core/config_fields.hpp"

namespace rownav::control {

/// Parameters of PurePursuitController.
struct PurePursuitConfig {
  double min_lookahead = 1.0;   ///< [m] lookahead at low speed
  double lookahead_time = 1.0;  ///< [s] lookahead grows as speed x this time (0: fixed)
  double max_lookahead = 4.0;   ///< [m] upper bound of the lookahead
  /// [m/s] speed used for omega = v kappa below this (lets the robot straighten up at start)
  double min_speed = 0.05;
  SlowdownConfig slowdown;  ///< speed reduction with the front obstacle distance (rownav)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("min_lookahead", s.min_lookahead);
    v("lookahead_time", s.lookahead_time);
    v("max_lookahead", s.max_lookahead);
    v("min_speed", s.min_speed);
    v("slowdown", s.slowdown);
  }
  void validate() const;
};

/// Pure pursuit path follower. Stateless apart from its config.
class PurePursuitController : public PathController {
 public:
  using Config = PurePursuitConfig;
  explicit PurePursuitController(const PurePursuitConfig& config = {});
  std::string_view name() const override { return "pure_pursuit"; }
  core::Twist2 compute(const ControlInput& in) override;
  void reset() override {}
  const PurePursuitConfig& config() const { return config_; }

 private:
  PurePursuitConfig config_;
};

}  // namespace rownav::control
