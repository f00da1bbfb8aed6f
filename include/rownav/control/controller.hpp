#pragma once
/// @file controller.hpp The interface of a path-following controller.
///
/// CONTRACT shared by control/, navigate/ and the closed-loop runner.
#include <limits>
#include <string_view>

#include "rownav/core/line2.hpp"
#include "rownav/core/twist.hpp"

namespace rownav::control {

/// What a controller sees each cycle. Errors follow track::RowTracking: lateral left +,
/// heading = robot minus path.
struct ControlInput {
  double stamp = 0.0;          ///< [s]
  double dt = 0.1;             ///< [s] since the previous cycle
  double lateral_error = 0.0;  ///< [m] base origin from the path (left +)
  double heading_error = 0.0;  ///< [rad] robot heading minus the path heading
  core::Line2 path_base;       ///< path to follow (a line) in the base frame, oriented forward
  double steepness = 0.0;      ///< [-] Malavazi 2018 steep-model indicator (0 when unknown)
  double speed_ref = 0.5;      ///< [m/s] desired forward speed
  double speed = 0.0;          ///< [m/s] current forward speed estimate
  /// [m] distance to the nearest obstacle in the front rectangle (infinity when clear)
  double obstacle_distance = std::numeric_limits<double>::infinity();
};

/// A path-following controller: (v, omega) from the tracked deviations. Small state (PID
/// integrators, FIR taps); never throws.
class PathController {
 public:
  virtual ~PathController() = default;
  virtual std::string_view name() const = 0;
  virtual core::Twist2 compute(const ControlInput& in) = 0;
  virtual void reset() = 0;
};

}  // namespace rownav::control
