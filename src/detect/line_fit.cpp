#include "rownav/detect/line_fit.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace rownav::detect {

std::optional<core::Line2> fit_line_tls(std::span<const Eigen::Vector2f> points) {
  if (points.size() < 2) return std::nullopt;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : points) mean += p.cast<double>();
  mean /= static_cast<double>(points.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector2d d = p.cast<double>() - mean;
    cov += d * d.transpose();
  }
  if (cov.trace() <= 1e-12) return std::nullopt;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  Eigen::Vector2d dir = eig.eigenvectors().col(1);  // largest eigenvalue: along the points
  if (dir.x() < 0.0) dir = -dir;
  return core::Line2(mean, dir);
}

core::RowLine make_row_line(const core::Line2& line, std::span<const Eigen::Vector2f> support) {
  core::RowLine r;
  r.line = line.direction.x() < 0.0 ? core::Line2(line.point, -line.direction) : line;
  r.heading = r.line.heading();
  r.offset = std::abs(r.line.direction.x()) > 1e-9 ? r.line.y_at(0.0) : r.line.point.y();
  r.support = static_cast<int>(support.size());
  double sq = 0.0;
  r.x_min = std::numeric_limits<double>::infinity();
  r.x_max = -std::numeric_limits<double>::infinity();
  for (const auto& p : support) {
    const double d = r.line.signed_distance(p.cast<double>());
    sq += d * d;
    r.x_min = std::min(r.x_min, static_cast<double>(p.x()));
    r.x_max = std::max(r.x_max, static_cast<double>(p.x()));
  }
  if (support.empty()) r.x_min = r.x_max = 0.0;
  r.rms = support.empty() ? 0.0 : std::sqrt(sq / static_cast<double>(support.size()));
  return r;
}

namespace {

double offset_at(const core::RowLine& r, double x) {
  return std::abs(r.line.direction.x()) > 1e-9 ? r.line.y_at(x) : r.offset;
}

// Confidence from the corridor rows: well supported, tight rows give values close to 1.
double corridor_confidence(const core::RowObservation& obs) {
  double c = 0.0;
  int n = 0;
  for (const int i : {obs.left, obs.right}) {
    if (i < 0) continue;
    const auto& r = obs.rows[static_cast<std::size_t>(i)];
    const double support = 1.0 - std::exp(-r.support / 15.0);
    const double tight = 1.0 / (1.0 + (r.rms / 0.15) * (r.rms / 0.15));
    c += support * tight;
    ++n;
  }
  return n == 0 ? 0.0 : c / 2.0;  // one side only: at most 0.5
}

// Angle between two row directions, folded to [0, pi/2].
double skew(const core::RowLine& a, const core::RowLine& b) {
  const double d = std::abs(a.line.direction.normalized().dot(b.line.direction.normalized()));
  return std::acos(std::min(1.0, d));
}

// [m] how far along x the row's returns start from the robot (0 when they pass beside it).
double start_distance(const core::RowLine& r) {
  return r.x_min > 0.0 ? r.x_min : r.x_max < 0.0 ? -r.x_max : 0.0;
}

// Rows of obs parallel to row i within max_skew (i included).
int companions(const core::RowObservation& obs, int i, double max_skew) {
  int n = 0;
  for (const auto& r : obs.rows) n += skew(r, obs.rows[std::size_t(i)]) <= max_skew;
  return n;
}

// The nearest corridor rows must be parallel; otherwise the side fewer rows agree with (then the
// one seen farther from the robot) takes its nearest row parallel to the other side, or none.
void pair_parallel(core::RowObservation& obs, double lookahead, double max_skew) {
  if (obs.left < 0 || obs.right < 0) return;
  const auto& l = obs.rows[std::size_t(obs.left)];
  const auto& r = obs.rows[std::size_t(obs.right)];
  if (skew(l, r) <= max_skew) return;
  const int nl = companions(obs, obs.left, max_skew), nr = companions(obs, obs.right, max_skew);
  const bool keep_left = nl != nr ? nl > nr : start_distance(l) <= start_distance(r);
  const int keep = keep_left ? obs.left : obs.right;
  int& loser = keep_left ? obs.right : obs.left;
  loser = -1;
  const auto& k = obs.rows[std::size_t(keep)];
  for (std::size_t i = 0; i < obs.rows.size(); ++i) {
    const double y = offset_at(obs.rows[i], lookahead);
    if ((keep_left ? y >= 0.0 : y < 0.0) || skew(obs.rows[i], k) > max_skew) continue;
    const bool nearer =
        loser < 0 || std::abs(y) < std::abs(offset_at(obs.rows[std::size_t(loser)], lookahead));
    if (nearer) loser = static_cast<int>(i);
  }
}

}  // namespace

void finalize_observation(core::RowObservation& obs, double lookahead,
                          const CorridorPairConfig& pair) {
  std::sort(obs.rows.begin(), obs.rows.end(), [&](const auto& a, const auto& b) {
    return offset_at(a, lookahead) < offset_at(b, lookahead);
  });
  obs.left = obs.right = -1;
  for (std::size_t i = 0; i < obs.rows.size(); ++i) {
    const double y = offset_at(obs.rows[i], lookahead);
    if (y < 0.0) obs.right = static_cast<int>(i);
    if (y >= 0.0 && obs.left < 0) obs.left = static_cast<int>(i);
  }
  pair_parallel(obs, lookahead, pair.max_skew_deg * std::numbers::pi / 180.0);
  if (std::isnan(obs.heading)) {
    double w = 0.0, h = 0.0;
    for (const auto& r : obs.rows) {
      w += r.support;
      h += r.support * r.heading;
    }
    obs.heading = w > 0.0 ? h / w : 0.0;
  }
  obs.corridor.reset();
  if (obs.left >= 0 && obs.right >= 0) {
    const auto& l = obs.rows[static_cast<std::size_t>(obs.left)];
    const auto& r = obs.rows[static_cast<std::size_t>(obs.right)];
    core::CorridorObservation c;
    c.offset = 0.5 * (l.offset + r.offset);
    c.heading = std::atan2(l.line.direction.y() + r.line.direction.y(),
                           l.line.direction.x() + r.line.direction.x());
    c.width = (l.offset - r.offset) * std::cos(c.heading);
    obs.corridor = c;
  }
  obs.status = obs.corridor       ? core::DetectionStatus::ok
               : obs.rows.empty() ? core::DetectionStatus::no_rows
                                  : core::DetectionStatus::degraded;
  if (obs.confidence <= 0.0) obs.confidence = corridor_confidence(obs);
}

}  // namespace rownav::detect
