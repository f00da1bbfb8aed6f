#pragma once
/// @file row_detector.hpp The interface every row detector implements.
#include <Eigen/Core>
#include <string_view>
#include <vector>

#include "rownav/core/detector_input.hpp"
#include "rownav/core/row_observation.hpp"

namespace rownav::detect {

/// One frame in the base frame (core/detector_input.hpp: the preprocessing makes it, every
/// detector reads it).
using DetectorInput = core::DetectorInput;

/// A per-frame row detector. detect() never throws: bad input gives status no_rows / degraded.
/// Detectors may keep state between frames (none of the current ones needs it), so detect() is
/// not const; one instance per thread.
class RowDetector {
 public:
  virtual ~RowDetector() = default;
  /// Short name, as on the command line (hough_skew, parallel_lines, pearl, ...).
  virtual std::string_view name() const = 0;
  virtual core::RowObservation detect(const DetectorInput& input) = 0;
};

}  // namespace rownav::detect
