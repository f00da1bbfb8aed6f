#pragma once
// Test double for the navigation stack: a proportional heading + lateral controller with no
// state, so the navigator tests do not depend on the real controllers' tuning (they pair it
// with the library's raw-corridor tracker, track/raw_corridor.hpp).
#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>

#include "rownav/control/controller.hpp"
#include "rownav/core/row_observation.hpp"
#include "rownav/track/row_tracker.hpp"

namespace rownav::test {

/// omega = -k_lat * lateral_error - k_head * heading_error, v = speed_ref (slower near obstacles).
class ProportionalController : public control::PathController {
 public:
  ProportionalController(double k_lat = 1.0, double k_head = 1.5)
      : k_lat_(k_lat), k_head_(k_head) {}
  std::string_view name() const override { return "proportional"; }
  void reset() override {}
  core::Twist2 compute(const control::ControlInput& in) override {
    if (!std::isfinite(in.lateral_error) || !std::isfinite(in.heading_error)) return {};
    const double w = -k_lat_ * in.lateral_error - k_head_ * in.heading_error;
    double v = in.speed_ref;
    if (std::isfinite(in.obstacle_distance)) v *= std::clamp(in.obstacle_distance / 2.0, 0.0, 1.0);
    return {v, 0.0, std::clamp(w, -1.0, 1.0)};
  }

 private:
  double k_lat_, k_head_;
};

}  // namespace rownav::test
