// Lan 2021 line EKF: odometry prediction of (a, b_l, b_r), update from the left / right rows.
#include "rownav/track/line_ekf.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <vector>

namespace rownav::track {

namespace {

/// The state moved by the odometry increment: both lines share the slope (Lan 2021 eq. (23)).
Eigen::Vector3d move_state(const Eigen::Vector3d& x, const core::Pose2& T_prev_now) {
  const SlopeIntercept l = move_line(SlopeIntercept{x(0), x(1)}, T_prev_now);
  const SlopeIntercept r = move_line(SlopeIntercept{x(0), x(2)}, T_prev_now);
  return {0.5 * (l.a + r.a), l.b, r.b};
}

bool finite_row(const core::RowLine& r) {
  return std::isfinite(r.offset) && std::isfinite(r.heading) && std::abs(r.heading) < 1.4;
}

/// One measured row: its side (0 left, 1 right) and slope / intercept.
struct Measured {
  int side = 0;
  double a = 0.0, b = 0.0;
};

}  // namespace

void LineEkfConfig::validate() const {
  core::check_positive(init_sigma_slope, "init_sigma_slope");
  core::check_positive(init_sigma_offset, "init_sigma_offset");
  core::check_non_negative(process_slope_per_m, "process_slope_per_m");
  core::check_non_negative(process_offset_per_m, "process_offset_per_m");
  core::check_non_negative(process_slope_per_s, "process_slope_per_s");
  core::check_non_negative(process_offset_per_s, "process_offset_per_s");
  core::check_positive(meas_sigma_slope, "meas_sigma_slope");
  core::check_positive(meas_sigma_offset, "meas_sigma_offset");
  core::check_positive(gate, "gate");
  core::check_range(max_rejections, 1, 100000, "max_rejections");
  core::check_range(association_zone, 0.05, 1.0, "association_zone");
  core::validate_nested(common, "common");
}

LineEkfTracker::LineEkfTracker(const LineEkfConfig& config)
    : TrackerBase((config.validate(), config.common)), config_(config) {}

void LineEkfTracker::predict(const core::Pose2& T_prev_now, const core::Pose2&, double dt) {
  // EKF prediction with the odometry increment as input (Lan 2021 sec. 3); Jacobian by central
  // differences (the line transform is smooth, 3 x 3).
  Eigen::Matrix3d F;
  for (int i = 0; i < 3; ++i) {
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d(i) = 1e-6;
    F.col(i) = (move_state(x_ + d, T_prev_now) - move_state(x_ - d, T_prev_now)) / 2e-6;
  }
  x_ = move_state(x_, T_prev_now);
  const double dist = T_prev_now.translation().norm();
  const double qa = std::pow(config_.process_slope_per_m, 2) * dist +
                    std::pow(config_.process_slope_per_s, 2) * dt;
  const double qb = std::pow(config_.process_offset_per_m, 2) * dist +
                    std::pow(config_.process_offset_per_s, 2) * dt;
  P_ = F * P_ * F.transpose();
  P_.diagonal() += Eigen::Vector3d(qa, qb, qb);
}

bool LineEkfTracker::initialise(const core::RowObservation& obs) {
  const bool l = obs.left >= 0 && finite_row(obs.rows[std::size_t(obs.left)]);
  const bool r = obs.right >= 0 && finite_row(obs.rows[std::size_t(obs.right)]);
  if (!l && !r) return false;
  const double spacing = common().default_row_spacing;
  const auto& L = obs.rows[std::size_t(l ? obs.left : obs.right)];
  const auto& R = obs.rows[std::size_t(r ? obs.right : obs.left)];
  x_ = {std::tan(0.5 * (L.heading + R.heading)), l ? L.offset : R.offset + spacing,
        r ? R.offset : L.offset - spacing};
  const double sa = config_.init_sigma_slope, sb = config_.init_sigma_offset;
  P_ = Eigen::Vector3d(sa * sa, sb * sb * (l ? 1.0 : 4.0), sb * sb * (r ? 1.0 : 4.0)).asDiagonal();
  initialised_ = true;
  rejections_ = 0;
  created_ = last_seen_ = obs.stamp;
  updates_ = 1;
  for (int s = 0; s < 2; ++s) {
    const auto& row = s == 0 ? L : R;
    x_min_[s] = row.x_min, x_max_[s] = row.x_max;
  }
  return true;
}

bool LineEkfTracker::correct(const core::RowObservation& obs, const core::Pose2&) {
  stamp_ = obs.stamp;
  if (!initialised_) return initialise(obs);
  // Association: per side the observed row nearest the predicted intercept, within a zone
  // scaled by the width between the two lines (not the row spacing: issue 10).
  const double width = std::max(x_(1) - x_(2), 0.25 * common().default_row_spacing);
  std::vector<Measured> z;
  int pick[2] = {-1, -1};
  for (int s = 0; s < 2; ++s) {
    double best = config_.association_zone * width;
    for (std::size_t i = 0; i < obs.rows.size(); ++i) {
      const auto& r = obs.rows[i];
      if (!finite_row(r)) continue;
      const double d = std::abs(r.offset - x_(1 + s));
      if (d < best) best = d, pick[s] = static_cast<int>(i);
    }
    if (pick[s] >= 0) {
      const auto& r = obs.rows[std::size_t(pick[s])];
      z.push_back({s, std::tan(r.heading), r.offset});
    }
  }
  if (pick[0] >= 0 && pick[0] == pick[1]) z.pop_back();  // one row cannot be both sides
  if (z.empty()) return ++rejections_ >= config_.max_rejections && initialise(obs);
  const int m = 2 * static_cast<int>(z.size());
  Eigen::VectorXd y(m);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m, 3), R = Eigen::MatrixXd::Zero(m, m);
  for (std::size_t k = 0; k < z.size(); ++k) {
    const int i = 2 * static_cast<int>(k);
    H(i, 0) = 1.0;
    H(i + 1, 1 + z[k].side) = 1.0;
    y(i) = z[k].a - x_(0);
    y(i + 1) = z[k].b - x_(1 + z[k].side);
    R(i, i) = config_.meas_sigma_slope * config_.meas_sigma_slope;
    R(i + 1, i + 1) = config_.meas_sigma_offset * config_.meas_sigma_offset;
  }
  const Eigen::MatrixXd S = H * P_ * H.transpose() + R;
  const double d2 = y.dot(S.ldlt().solve(y));
  if (!std::isfinite(d2) || d2 > config_.gate * m / 2.0) {  // gate scaled with the dimension
    return ++rejections_ >= config_.max_rejections && initialise(obs);
  }
  const Eigen::MatrixXd K = P_ * H.transpose() * S.inverse();
  x_ += K * y;
  const Eigen::Matrix3d IKH = Eigen::Matrix3d::Identity() - K * H;
  P_ = IKH * P_ * IKH.transpose() + K * R * K.transpose();  // Joseph form
  rejections_ = 0;
  last_seen_ = obs.stamp;
  ++updates_;
  for (const auto& meas : z) {
    const auto& r = obs.rows[std::size_t(pick[meas.side])];
    x_min_[meas.side] = r.x_min, x_max_[meas.side] = r.x_max;
  }
  return true;
}

void LineEkfTracker::describe(RowTracking& out) const {
  for (int s = 1; s >= 0; --s) {  // right first: rows sorted right to left
    TrackedRow t;
    t.id = s == 0 ? 1 : 0;
    t.line_base = line_of({x_(0), x_(1 + s)});
    t.offset = x_(1 + s);
    t.heading = std::atan(x_(0));
    t.x_min = x_min_[s], t.x_max = x_max_[s];
    t.support = updates_;
    t.age = stamp_ - created_;
    t.last_seen = last_seen_;
    out.rows.push_back(t);
  }
  out.right = out.rows[0].offset < out.rows[1].offset ? 0 : -1;
  out.left = out.right == 0 ? 1 : -1;
  if (out.left < 0) out.rows.clear();  // crossed lines: no corridor
  // b_l - b_r is the width between the fitted lines (face to face for an opaque canopy), not the
  // row spacing: row_spacing stays 0 and TrackerBase gives the centre-to-centre one (issue 10).
  out.row_spacing = 0.0;
}

}  // namespace rownav::track
