#pragma once
/// @file pid.hpp A discrete PID with an integrator clamp (anti wind-up), shared by the
/// lookahead (Bertoglio 2023 sec. II-B) and FIR (Malavazi 2018 sec. 2.3.5) controllers.
#include "rownav/core/config_fields.hpp"

namespace rownav::control {

/// PID gains. The papers give none ("empirically tuned", Malavazi 2018 sec. 2.4); the defaults
/// are set per controller.
struct PidGains {
  double kp = 1.0;              ///< [output / error] proportional gain
  double ki = 0.0;              ///< [output / (error s)] integral gain
  double kd = 0.0;              ///< [output s / error] derivative gain
  double integral_limit = 0.5;  ///< [error s] |integral of the error| is clamped to this

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("kp", s.kp);
    v("ki", s.ki);
    v("kd", s.kd);
    v("integral_limit", s.integral_limit);
  }
  void validate() const;
};

/// Discrete PID: u = kp e + ki sum(e dt) + kd (e - e_prev) / dt. The derivative is 0 on the first
/// step after reset(). Non-finite e or dt <= 0: returns the proportional term only and keeps the
/// state. Never throws.
class Pid {
 public:
  explicit Pid(const PidGains& gains = {}) : gains_(gains) {}
  double update(double error, double dt);
  void reset();

 private:
  PidGains gains_;
  double integral_ = 0.0;
  double previous_ = 0.0;
  bool has_previous_ = false;
};

}  // namespace rownav::control
