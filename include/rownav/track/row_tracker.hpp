#pragma once
/// @file row_tracker.hpp The interface of a row tracker and its per-frame output.
///
/// CONTRACT shared by the trackers (model_matching, line_ekf, model_filter), navigate/ and the
/// closed-loop runner. Implementations may add fields but must keep these.
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/data_filter.hpp"
#include "rownav/core/line2.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/core/row_observation.hpp"

namespace rownav::track {

/// Tracking state of a frame.
enum class TrackStatus : std::uint8_t {
  tracking,  ///< the row models were updated by this frame's observation
  coasting,  ///< no usable observation: models carried by odometry (through a gap)
  lost       ///< no model, or coasting for longer than the tracker allows
};

/// A tracked row model expressed in the base frame of the current frame.
struct TrackedRow {
  int id = -1;             ///< persistent model id
  core::Line2 line_base;   ///< oriented towards +x
  double offset = 0.0;     ///< [m] lateral position at x = 0 (left +)
  double heading = 0.0;    ///< [rad] direction in the base frame
  double x_min = 0.0;      ///< [m] extent of the model's supporting points along x (base)
  double x_max = 0.0;      ///< [m]
  int support = 0;         ///< points / observations behind the model
  double age = 0.0;        ///< [s] since the model was created
  double last_seen = 0.0;  ///< [s] stamp of the last observation that updated it
  /// [m] lateral position at x = 0 of the row's centre line (left +): line_base is the fitted
  /// (corridor-side) line, the centre stands behind it (core::RowLine::centre_shift, issue 10).
  /// Trackers may leave it NaN: TrackerBase then fills it from the recent observations.
  double centre_offset = std::numeric_limits<double>::quiet_NaN();
  double half_width = 0.0;  ///< [m] canopy half width (0: unknown)
};

/// [m] lateral position at x = 0 (left +) of a tracked row's canopy edge towards `side` (+1:
/// its left edge, -1: its right edge): the centre line +- the half width, or the fitted line
/// itself when that is already the face (a planar scan: no centre line, no half width).
inline double edge_offset(const TrackedRow& r, double side) {
  if (std::isfinite(r.centre_offset) && r.half_width > 0.0)
    return r.centre_offset + side * r.half_width;
  return r.offset;
}

/// A tracker's answer for one frame.
struct RowTracking {
  double stamp = 0.0;  ///< [s]
  TrackStatus status = TrackStatus::lost;
  double confidence = 0.0;  ///< [0, 1]
  /// [m] signed offset of the base origin from the corridor centre line (left +); the corridor
  /// detector's CorridorObservation::offset is -lateral_error.
  double lateral_error = 0.0;
  double heading_error = 0.0;    ///< [rad] robot heading minus the corridor heading
  core::Line2 centre_line_base;  ///< corridor centre line in the base frame, oriented forward
  /// [m] row spacing, centre line to centre line, from every tracked row (robust to a missing
  /// row, track/row_geometry.hpp robust_spacing; 0: unknown). Never the corridor width: an
  /// opaque canopy's fitted lines are its faces (issue 10).
  double row_spacing = 0.0;
  /// [m] between the followed rows' fitted lines (face to face for an opaque canopy), the last
  /// one measured when a side is missing (0: unknown); a single row's corridor centre lies half
  /// of it away
  double corridor_width = 0.0;
  std::vector<TrackedRow> rows;  ///< tracked models, sorted right (y < 0) to left
  int left = -1;                 ///< index in rows of the followed left row, -1 if none
  int right = -1;                ///< index in rows of the followed right row, -1 if none
  /// [m] signed offset from the chosen implement row + offset (TrackerConfig::target_row), when
  /// one is configured and tracked.
  std::optional<double> target_lateral_error;
  double steepness = 0.0;  ///< [-] |tan| of the followed models' angle (Malavazi 2018 safety)
  double time_since_observation = 0.0;  ///< [s] since the last frame with rows
  /// [m] pre-control error of Malavazi 2018 sec. 2.3.3 (model_filter only, FIR-filtered): the
  /// lateral error, or with steep models the signed distance to where the robot would cross the
  /// model it heads into (left +: the robot must steer right).
  std::optional<double> distance_to_target;
};

/// The followed pair's inner canopy edges at x = 0 (base frame, left +): the right row's left
/// edge and the left row's right edge (edge_offset), with the rows themselves.
struct InnerFaces {
  const TrackedRow* right = nullptr;
  const TrackedRow* left = nullptr;
  double right_face = 0.0;  ///< [m]
  double left_face = 0.0;   ///< [m]
};

/// InnerFaces of `t`; nullopt unless both followed rows are set (the values may be non-finite).
inline std::optional<InnerFaces> inner_faces(const RowTracking& t) {
  const int n = static_cast<int>(t.rows.size());
  if (t.left < 0 || t.right < 0 || t.left >= n || t.right >= n) return std::nullopt;
  const TrackedRow& r = t.rows[static_cast<std::size_t>(t.right)];
  const TrackedRow& l = t.rows[static_cast<std::size_t>(t.left)];
  return InnerFaces{&r, &l, edge_offset(r, 1.0), edge_offset(l, -1.0)};
}

/// A row tracker. update() never throws: stale frames, time going backwards, odometry jumps and
/// no_rows observations are reflected in the status.
class RowTracker {
 public:
  virtual ~RowTracker() = default;
  /// Short name as on the command line (model_matching, line_ekf, model_filter).
  virtual std::string_view name() const = 0;
  /// One frame: the detector's observation (base frame at obs.stamp) and the odometry pose of
  /// the base at that stamp.
  virtual RowTracking update(const core::RowObservation& obs, const core::Pose2& T_odom_base) = 0;
  /// Forgets every model (e.g. after a headland turn, before entering the next corridor).
  virtual void reset() = 0;
  /// The data-filter boxes for a frame whose base is at `T_odom_base` (Malavazi 2018 sec.
  /// 2.3.1: the followed models select the next scan's points); nullopt: the tracker filters
  /// nothing (every tracker but model_filter).
  virtual std::optional<core::DataFilterBoxes> data_filter(const core::Pose2& T_odom_base) const {
    (void)T_odom_base;
    return std::nullopt;
  }
  /// The robot is manoeuvring (a headland turn): its frames see the rows at every angle, and a
  /// tracker keeps what it learnt of the field's geometry instead of learning from them. The
  /// default ignores it.
  virtual void set_manoeuvring(bool manoeuvring) { (void)manoeuvring; }
};

}  // namespace rownav::track

template <>
struct rownav::core::EnumNames<rownav::track::TrackStatus> {
  using E = rownav::track::TrackStatus;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::tracking, "tracking"}, {E::coasting, "coasting"}, {E::lost, "lost"}}};
};
