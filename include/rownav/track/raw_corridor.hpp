#pragma once
/// @file raw_corridor.hpp The "unfiltered" tracker (`none` on the command line): the detector's
/// corridor of each frame as it is, carried by odometry only through frames without rows.
/// It is the baseline the filtered trackers are compared with (Malavazi 2018, 004 Tables 1-3
/// "unfiltered" variants) and what a user gets without a tracker.
#include <optional>
#include <string_view>

#include "rownav/core/config_fields.hpp"
#include "rownav/track/row_tracker.hpp"

namespace rownav::track {

/// Configuration of the raw-corridor tracker.
struct RawCorridorConfig {
  /// [s] carrying the last corridor by odometry longer than this without an observation: lost
  double max_coast_time = 1.0;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("max_coast_time", s.max_coast_time);
  }
  void validate() const;
};

/// RowObservation::corridor -> RowTracking, no filtering; coasting on odometry through gaps.
class RawCorridorTracker : public RowTracker {
 public:
  explicit RawCorridorTracker(const RawCorridorConfig& config = {});
  std::string_view name() const override { return "none"; }
  RowTracking update(const core::RowObservation& obs, const core::Pose2& T_odom_base) override;
  void reset() override { last_.reset(); }

 private:
  struct Last {
    double stamp = 0.0;
    core::Line2 centre_odom;  // corridor centre line in the odom frame
  };
  RawCorridorConfig config_;
  double spacing_ = 0.0;
  std::optional<Last> last_;
};

}  // namespace rownav::track
