#pragma once
/// @file odometry_scale_estimator.hpp Online estimate of the wheel odometry's correction factor
/// alpha (Bertoglio 2023, 003_25dc0df51a1e5faf.txt eq. (2)) from the LiDAR: every straight
/// stretch of `baseline` metres, the frames at its two ends are matched (scan_scale_match.hpp)
/// and alpha x the measured scale is one sample; the median of the last samples becomes the
/// odometry's alpha once they agree. The paper calibrates alpha off-line "following the
/// directions provided in [10]"; issue 11 asks for it online, because tyre pressure, load and
/// ground change it between calibrations.
#include <Eigen/Core>
#include <deque>
#include <optional>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/localize/scan_scale_match.hpp"

namespace rownav::localize {

/// When samples are taken and when they change alpha.
struct OdometryScaleConfig {
  /// Estimate alpha online from the LiDAR frames (NavStack feeds them); false: the robot file's
  /// (or the nominal) alpha is kept
  bool enabled = false;
  /// [m] odometry distance between the two frames of a sample: the scale's resolution is
  /// match.resolution / baseline (4 % a coarse step at 1 m, refined to a quarter and a parabola)
  double baseline = 1.0;
  /// [deg] a stretch that turns more than this is no sample (the frames' overlap and the gyro's
  /// heading, which the match trusts, are best on straight drives; rownav)
  double max_heading_change_deg = 5.0;
  int window = 15;      ///< [-] samples kept; alpha is their median (rownav)
  int min_samples = 5;  ///< [-] samples needed before alpha changes (rownav)
  /// [-] median absolute deviation of the window above which alpha is not changed: samples that
  /// disagree are a field that fools the match, not a drive train (rownav)
  double max_spread = 0.03;
  /// [-] the median must differ from the current alpha by more than this to replace it (no
  /// change for the noise of one more sample; rownav)
  double min_change = 0.005;
  ScanScaleMatchConfig match;  ///< the comparison of two frames

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("enabled", s.enabled);
    v("baseline", s.baseline);
    v("max_heading_change_deg", s.max_heading_change_deg);
    v("window", s.window);
    v("min_samples", s.min_samples);
    v("max_spread", s.max_spread);
    v("min_change", s.min_change);
    v("match", s.match);
  }
  void validate() const;
};

/// Keeps the frame at the start of the current straight stretch and the window of samples.
/// Never throws on data.
class OdometryScaleEstimator {
 public:
  /// Validates `config` (throws std::invalid_argument naming the field).
  explicit OdometryScaleEstimator(const OdometryScaleConfig& config = {});
  /// A frame's points (its base frame) and its odometry pose, integrated with `alpha`. Returns
  /// the alpha the odometry should take from now on, when the samples say so.
  std::optional<double> add_frame(const std::vector<Eigen::Vector2f>& points_base,
                                  const core::Pose2& T_odom_base, double alpha);
  /// Frames compared so far, and how many gave a sample.
  int matches() const { return matches_; }
  int accepted() const { return accepted_; }
  const OdometryScaleConfig& config() const { return config_; }

 private:
  struct Key {
    std::vector<Eigen::Vector2f> points;
    core::Pose2 T_odom_base;
    double alpha = 1.0;
  };
  std::optional<double> take(double sample, double alpha);

  OdometryScaleConfig config_;
  std::optional<Key> key_;
  std::deque<double> samples_;
  int matches_ = 0, accepted_ = 0;
};

}  // namespace rownav::localize
