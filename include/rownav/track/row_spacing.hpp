#pragma once
/// @file row_spacing.hpp Row spacing centre to centre from every row seen (issue 10): each
/// usable frame gives the robust spacing of its rows' centre lines (core::centre_offset, the
/// fitted line moved under the canopy's crown); the estimate is the median of the latest frames.
/// The followed rows' centre shifts and half widths are kept the same way, per side.
#include <array>
#include <deque>

#include "rownav/core/row_observation.hpp"

namespace rownav::track {

/// Running row spacing and followed-row profiles. Never throws.
class RowSpacingEstimator {
 public:
  /// window: [frames] the median runs over the latest `window` frames.
  explicit RowSpacingEstimator(int window = 50) : window_(window) {}
  /// One usable frame: every row's centre; the left / right rows' centre shift and half width.
  void add(const core::RowObservation& obs);
  /// [m] median of the recent per-frame spacings, 0 when none.
  double spacing() const;
  /// [m] recent median centre shift (away from the robot) of the followed row on a side.
  double shift(bool left) const;
  /// [m] recent median canopy half width of the followed row on a side (0: unknown).
  double half_width(bool left) const;
  void reset();

 private:
  int window_;
  std::deque<double> spacings_;
  std::array<std::deque<double>, 2> shifts_, half_widths_;  // [0] right, [1] left
};

}  // namespace rownav::track
