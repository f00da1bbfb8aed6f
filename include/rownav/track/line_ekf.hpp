#pragma once
/// @file line_ekf.hpp Extended Kalman filter on the two followed row lines (Lan 2021,
/// 001_b5f4b55a1b95775a.txt sec. 3, eq. (23)): state (a, b_l, b_r) of L_l: y = a x + b_l and
/// L_r: y = a x + b_r in the base frame; the prediction moves the lines by the odometry
/// increment (Delta x, Delta y, Delta theta), the update takes the detector's left / right rows.
///
/// The paper gives no noise values; the defaults below are rownav's, sized for a 10 Hz LiDAR and
/// wheel odometry (documented per field).
#include <Eigen/Core>

#include "rownav/core/config_fields.hpp"
#include "rownav/track/tracker_base.hpp"

namespace rownav::track {

/// Parameters of LineEkfTracker (noise: rownav, Lan 2021 gives none).
struct LineEkfConfig {
  double init_sigma_slope = 0.05;       ///< [-] initial std of a
  double init_sigma_offset = 0.10;      ///< [m] initial std of b_l, b_r
  double process_slope_per_m = 0.01;    ///< [-/sqrt(m)] slope random walk per metre driven
  double process_offset_per_m = 0.01;   ///< [m/sqrt(m)] intercept random walk per metre driven
  double process_slope_per_s = 0.003;   ///< [-/sqrt(s)] slope random walk per second
  double process_offset_per_s = 0.003;  ///< [m/sqrt(s)] intercept random walk per second
  double meas_sigma_slope = 0.02;       ///< [-] std of a detected row's slope
  double meas_sigma_offset = 0.04;      ///< [m] std of a detected row's intercept
  /// [-] Mahalanobis distance squared above which a measurement is rejected (chi2, 2 dof, 99.9 %)
  double gate = 13.8;
  /// [-] consecutive rejected frames after which the filter re-initialises from the observation
  /// (like Malavazi 2018's permanence counter)
  int max_rejections = 5;
  /// [-] an observed row is taken for a side only within this fraction of the spacing of the
  /// predicted line
  double association_zone = 0.4;
  TrackerConfig common;  ///< coasting, odometry plausibility, implement target

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("init_sigma_slope", s.init_sigma_slope);
    v("init_sigma_offset", s.init_sigma_offset);
    v("process_slope_per_m", s.process_slope_per_m);
    v("process_offset_per_m", s.process_offset_per_m);
    v("process_slope_per_s", s.process_slope_per_s);
    v("process_offset_per_s", s.process_offset_per_s);
    v("meas_sigma_slope", s.meas_sigma_slope);
    v("meas_sigma_offset", s.meas_sigma_offset);
    v("gate", s.gate);
    v("max_rejections", s.max_rejections);
    v("association_zone", s.association_zone);
    v("common", s.common);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// Lan 2021 line EKF as a RowTracker.
class LineEkfTracker : public TrackerBase {
 public:
  /// Validates the config (throws std::invalid_argument).
  explicit LineEkfTracker(const LineEkfConfig& config = {});
  std::string_view name() const override { return "line_ekf"; }
  const LineEkfConfig& config() const { return config_; }
  /// State (a, b_l, b_r) and its covariance (valid while tracking / coasting).
  const Eigen::Vector3d& state() const { return x_; }
  const Eigen::Matrix3d& covariance() const { return P_; }

 protected:
  bool has_model() const override { return initialised_; }
  void clear_models() override { initialised_ = false, rejections_ = 0; }
  void predict(const core::Pose2& T_prev_now, const core::Pose2& T_odom_base, double dt) override;
  bool correct(const core::RowObservation& obs, const core::Pose2& T_odom_base) override;
  void describe(RowTracking& out) const override;

 private:
  bool initialise(const core::RowObservation& obs);

  LineEkfConfig config_;
  bool initialised_ = false;
  int rejections_ = 0;
  Eigen::Vector3d x_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d P_ = Eigen::Matrix3d::Identity();
  double created_ = 0.0, last_seen_ = 0.0, stamp_ = 0.0;
  int updates_ = 0;
  double x_min_[2] = {0.0, 0.0}, x_max_[2] = {0.0, 0.0};  // left, right extents
};

}  // namespace rownav::track
