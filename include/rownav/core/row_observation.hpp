#pragma once
/// @file row_observation.hpp What a row detector sees in one frame: the common heading, every
/// visible row as a line in the robot frame, and the corridor the robot is in.
#include <array>
#include <cmath>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/line2.hpp"

namespace rownav::core {

/// Outcome of a per-frame step. Per-frame code never throws; it reports one of these.
enum class DetectionStatus : std::uint8_t {
  ok,        ///< rows found on both sides of the robot
  degraded,  ///< a usable but partial answer (one side only, few points, low confidence)
  no_rows    ///< nothing row-like in the frame (empty, all invalid, open field, wall...)
};

/// One detected row in the robot (base) frame, x forward, y left.
struct RowLine {
  Line2 line;          ///< oriented towards +x
  double offset = 0.0;   ///< [m] signed lateral position at x = 0 (left +): line.y_at(0)
  double heading = 0.0;  ///< [rad] direction of the row, (-pi/2, pi/2)
  double x_min = 0.0;    ///< [m] extent of the supporting points along x
  double x_max = 0.0;    ///< [m]
  int support = 0;       ///< points assigned to the row
  double rms = 0.0;      ///< [m] RMS perpendicular distance of the support to the line
  /// [m] from `line` to the row's centre line, across the row, away from the robot (issue 10).
  /// `line` is what the detector fits: the corridor-side face for an opaque canopy (a solid
  /// hedge), the trunk line when trunks are seen; the centre line stands under the canopy's
  /// crown (detect/row_profile.hpp). 0 when unknown (2D scans): the line is the centre.
  double centre_shift = 0.0;
  /// [m] canopy half width: the inner face lies this far from the centre line towards the
  /// robot (issue 10; 0 when unknown)
  double half_width = 0.0;
  /// `line` is the row's centre line already (a line through trunk centres,
  /// detect/trunk_lines.hpp): the row profile keeps centre_shift 0 and measures only half_width
  bool centre_line = false;
};

/// [m] lateral position at x = 0 of the row's centre line (left +): the fitted line moved by
/// centre_shift away from the robot. Row spacing is centre to centre (issue 10).
inline double centre_offset(const RowLine& r) {
  const double c = std::abs(r.line.direction.normalized().x());
  const double out = r.offset >= 0.0 ? 1.0 : -1.0;
  return r.offset + out * r.centre_shift / (c > 1e-3 ? c : 1e-3);
}

/// A corridor observation: the centre line between the two rows around the robot.
struct CorridorObservation {
  double offset = 0.0;   ///< [m] lateral position of the corridor centre at x = 0 (left +);
                         ///< the robot's lateral error is -offset
  double heading = 0.0;  ///< [rad] corridor direction in the robot frame; the robot's heading
                         ///< error is -heading
  /// [m] free width between the two rows' fitted lines (face to face for opaque canopies, 0
  /// when unknown). NOT the row spacing (centre to centre, issue 10): never use it as one.
  double width = 0.0;
};

/// A detector's answer for one frame.
struct RowObservation {
  double stamp = 0.0;  ///< [s] of the frame
  DetectionStatus status = DetectionStatus::no_rows;
  double confidence = 0.0;      ///< [0, 1]
  double heading = 0.0;         ///< [rad] common row heading in the robot frame
  std::vector<RowLine> rows;    ///< every visible row, sorted by offset, right (y < 0) to left
  int left = -1;   ///< index in rows of the nearest row on the left (offset > 0), -1 if none
  int right = -1;  ///< index in rows of the nearest row on the right (offset < 0), -1 if none
  std::optional<CorridorObservation> corridor;  ///< between rows[right] and rows[left]
};

}  // namespace rownav::core

template <>
struct rownav::core::EnumNames<rownav::core::DetectionStatus> {
  using E = rownav::core::DetectionStatus;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::ok, "ok"}, {E::degraded, "degraded"}, {E::no_rows, "no_rows"}}};
};
