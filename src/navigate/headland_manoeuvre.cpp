// Headland manoeuvres: turn choice, primitive paths (rotate / follow) in the turn frame, the
// pure-pursuit follower on the odometry pose and the re-anchoring on row ends.
#include "rownav/navigate/headland_manoeuvre.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "rownav/core/angle.hpp"

namespace rownav::navigate {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kArcStep = 0.1;  // [m] path sampling
constexpr double kRadiusMargin = 1.25;  // [-] turn radius / min turn radius (car-like robots)

/// Points of an arc around c from a to b (same radius), counter-clockwise when ccw.
std::vector<Eigen::Vector2d> arc(const Eigen::Vector2d& c, const Eigen::Vector2d& a,
                                 const Eigen::Vector2d& b, bool ccw) {
  const double r = (a - c).norm();
  const double a0 = std::atan2(a.y() - c.y(), a.x() - c.x());
  double a1 = std::atan2(b.y() - c.y(), b.x() - c.x());
  if (ccw)
    while (a1 <= a0 + 1e-9) a1 += 2.0 * kPi;
  else
    while (a1 >= a0 - 1e-9) a1 -= 2.0 * kPi;
  const int n = std::max(2, static_cast<int>(std::ceil(std::abs(a1 - a0) * r / kArcStep)) + 1);
  std::vector<Eigen::Vector2d> out;
  for (int i = 0; i < n; ++i) {
    const double t = a0 + (a1 - a0) * i / (n - 1);
    out.emplace_back(c.x() + r * std::cos(t), c.y() + r * std::sin(t));
  }
  return out;
}

void append(std::vector<Eigen::Vector2d>& path, const std::vector<Eigen::Vector2d>& more) {
  for (const auto& p : more)
    if (path.empty() || (p - path.back()).norm() > 1e-6) path.push_back(p);
}

/// Resamples a path every kArcStep (with its anchor weights) so the pursuit cursor can advance.
void densify(std::vector<Eigen::Vector2d>& path, std::vector<double>& w) {
  std::vector<Eigen::Vector2d> p;
  std::vector<double> ww;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const int n =
        std::max(1, static_cast<int>(std::ceil((path[i + 1] - path[i]).norm() / kArcStep)));
    for (int k = 0; k < n; ++k) {
      const double t = static_cast<double>(k) / n;
      p.push_back(path[i] + t * (path[i + 1] - path[i]));
      ww.push_back(w[i] + t * (w[i + 1] - w[i]));
    }
  }
  p.push_back(path.back());
  ww.push_back(w.back());
  path = std::move(p);
  w = std::move(ww);
}

/// Weight of the target correction along a path: its cumulative length fraction.
std::vector<double> ramp(const std::vector<Eigen::Vector2d>& path) {
  std::vector<double> w(path.size(), 0.0);
  double total = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) total += (path[i] - path[i - 1]).norm();
  double acc = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    acc += (path[i] - path[i - 1]).norm();
    w[i] = total > 0.0 ? acc / total : 1.0;
  }
  return w;
}

}  // namespace

void ManoeuvreConfig::validate() const {
  core::check_positive(turn_speed, "turn_speed");
  core::check_positive(rotate_rate, "rotate_rate");
  core::check_range(heading_tolerance_deg, 0.1, 20.0, "heading_tolerance_deg");
  core::check_positive(lookahead, "lookahead");
  core::check_range(anchor_gate, 0.05, 0.5, "anchor_gate");
  core::check_positive(pole_band, "pole_band");
}

int min_feasible_shift(double spacing, double min_turn_radius) {
  if (!(spacing > 0.0) || !(min_turn_radius > 0.0)) return 1;
  return std::max(1, static_cast<int>(
                        std::ceil(2.0 * kRadiusMargin * min_turn_radius / spacing - 1e-9)));
}

TurnPlan choose_turn(ManoeuvreChoice choice, int shift, double spacing, const TurnAbility& robot) {
  const double lateral = std::max(1, shift) * spacing;
  const bool in_place_ok = robot.can_turn_in_place;
  if ((choice == ManoeuvreChoice::automatic || choice == ManoeuvreChoice::in_place) && in_place_ok)
    return {TurnKind::in_place, 0.0, true};
  // Lan 2021 (001 sec. 3.3): fixed radius = spacing / 2; never below the robot's minimum.
  // A car-like robot gets kRadiusMargin x its minimum: its steering takes ~1 s to swing from
  // lock to lock between the arcs, and it needs curvature to spare to come back onto the path.
  const double r = std::max(spacing / 2.0, kRadiusMargin * robot.min_turn_radius);
  if (choice != ManoeuvreChoice::three_point && lateral >= 2.0 * r - 1e-9)
    return {TurnKind::u_turn, r, in_place_ok};
  return {TurnKind::bulb, r, in_place_ok};
}

HeadlandManoeuvre::HeadlandManoeuvre(const ManoeuvreConfig& config, const TurnPlan& plan,
                                     const core::Pose2& T_odom_turn, int shift, TurnSide side,
                                     double spacing, double exit_distance)
    : config_(config),
      plan_(plan),
      T_odom_turn_(T_odom_turn),
      side_(side_sign(side)),
      shift_(std::max(1, shift)),
      spacing_(spacing > 0.0 ? spacing : 1.0) {
  planned_y_ = target_y_ = side_ * shift_ * spacing_;
  const double e = std::max(0.0, exit_distance);
  exit_x_ = e;
  if (plan.kind == TurnKind::in_place)
    build_in_place(e);
  else if (plan.kind == TurnKind::u_turn)
    build_u_turn(e, plan.radius);
  else
    build_bulb(e, plan.radius);
  for (auto& p : primitives_)
    if (!p.rotate) densify(p.path, p.anchor);
}

void HeadlandManoeuvre::build_in_place(double e) {
  // Bertoglio 2023 sec. II-B/C: rotate 90 deg, drive along the row ends, rotate 90 deg.
  primitives_.push_back({true, side_ * kPi / 2.0, {}, {}, false, false});
  Primitive leg;
  leg.path = {{e, 0.0}, {e, planned_y_}};
  leg.anchor = {0.0, 1.0};
  leg.headland = true;
  primitives_.push_back(leg);
  primitives_.push_back({true, kPi, {}, {}, false, false});
}

void HeadlandManoeuvre::build_u_turn(double e, double r) {
  // Lan 2021: semicircle of radius spacing / 2 for k = 1; arc - straight - arc for k > 1.
  const double D = shift_ * spacing_, s = side_;
  const bool ccw = side_ > 0;
  Primitive p;
  if (D <= 2.0 * r + 1e-9) {
    const Eigen::Vector2d c(e, s * D / 2.0);
    p.path = arc(c, {e, 0.0}, {e, s * D}, ccw);
  } else {
    append(p.path, arc({e, s * r}, {e, 0.0}, {e + r, s * r}, ccw));
    append(p.path, {{e + r, s * (D - r)}});
    append(p.path, arc({e, s * (D - r)}, {e + r, s * (D - r)}, {e, s * D}, ccw));
  }
  p.anchor = ramp(p.path);
  primitives_.push_back(p);
}

void HeadlandManoeuvre::build_bulb(double e, double r) {
  // Omega turn: away from the side, a large loop towards it, back into the target corridor.
  const double D = shift_ * spacing_, s = side_;
  const Eigen::Vector2d c1(e, -s * r), c3(e, s * (D + r));
  const double h = std::sqrt(std::max(0.0, 4.0 * r * r - std::pow(D / 2.0 + r, 2)));
  const Eigen::Vector2d c2(e + h, s * D / 2.0);
  const Eigen::Vector2d t12 = (c1 + c2) / 2.0, t23 = (c2 + c3) / 2.0;
  const bool ccw = side_ > 0;
  Primitive p;
  append(p.path, arc(c1, {e, 0.0}, t12, !ccw));
  append(p.path, arc(c2, t12, t23, ccw));
  append(p.path, arc(c3, t23, {e, s * D}, !ccw));
  p.anchor = ramp(p.path);
  primitives_.push_back(p);
}

core::Line2 HeadlandManoeuvre::entry_line_odom() const {
  return core::Line2({exit_x_, target_y_}, {-1.0, 0.0}).transformed(T_odom_turn_);
}

std::vector<Eigen::Vector2d> HeadlandManoeuvre::path_odom() const {
  std::vector<Eigen::Vector2d> out;
  for (const auto& p : primitives_)
    for (std::size_t i = 0; i < p.path.size(); ++i)
      out.push_back(
          T_odom_turn_ *
          Eigen::Vector2d(p.path[i] + Eigen::Vector2d(0, p.anchor[i] * (target_y_ - planned_y_))));
  return out;
}

void HeadlandManoeuvre::reanchor(const std::vector<Eigen::Vector2d>& ends_turn,
                                 const Eigen::Vector2d& robot) {
  // Row ends near the row-end line, merged over the frames (odometry keeps them put).
  for (const auto& q : ends_turn) {
    if (!q.allFinite() || std::abs(q.x()) > config_.pole_band) continue;
    // One row end per anchor gate: a canopy seen from the headland gives end estimates spread
    // across its width (crowns, a vine's foliage); two rows are a spacing apart.
    const double merge = config_.anchor_gate * spacing_;
    auto it = std::find_if(poles_.begin(), poles_.end(),
                           [&](const Pole& p) { return std::abs(p.y - q.y()) < merge; });
    if (it == poles_.end()) {
      poles_.push_back({q.y(), 1});
    } else {
      it->y = (it->y * it->n + q.y()) / (it->n + 1);
      ++it->n;
    }
  }
  // Rows passed abeam: the row ends between the exit corridor and the robot (003 sec. II-C).
  int passed = 0;
  for (const auto& p : poles_)
    if (side_ * p.y > 0.0 && side_ * p.y < side_ * robot.y()) ++passed;
  rows_passed_ = std::max(rows_passed_, passed);
  // The target corridor lies between the two row ends that flank the planned centre.
  const double gate = config_.anchor_gate * spacing_;
  std::optional<double> lo, hi;
  for (const auto& p : poles_) {
    if (p.n < 2) continue;
    if (std::abs(p.y - (planned_y_ - spacing_ / 2.0)) < gate) lo = p.y;
    if (std::abs(p.y - (planned_y_ + spacing_ / 2.0)) < gate) hi = p.y;
  }
  // Only abeam of the target: its two flanking row ends are then on either side of the robot and
  // the bias of each end's nearest point towards the robot cancels in the midpoint.
  if (lo && hi && std::abs(robot.y() - target_y_) < 0.5 * spacing_) target_y_ = (*lo + *hi) / 2.0;
}

core::Twist2 HeadlandManoeuvre::follow(Primitive& p, const core::Pose2& T_turn_base) {
  const double dy = target_y_ - planned_y_;
  auto point = [&](std::size_t i) {
    return Eigen::Vector2d(p.path[i] + Eigen::Vector2d(0, p.anchor[i] * dy));
  };
  const Eigen::Vector2d q = T_turn_base.translation();
  const std::size_t last = p.path.size() - 1;
  while (cursor_ < last && (point(cursor_ + 1) - q).norm() <= (point(cursor_) - q).norm() + 0.02)
    ++cursor_;
  // Done once the robot has passed the last point along the last segment.
  const Eigen::Vector2d end = point(last), prev = point(last > 0 ? last - 1 : 0);
  const Eigen::Vector2d dir = (end - prev).norm() > 1e-9
                                  ? Eigen::Vector2d((end - prev).normalized())
                                  : Eigen::Vector2d::UnitX();
  if (cursor_ + 2 >= last && dir.dot(q - end) > -0.03) {
    ++index_;
    cursor_ = 0;
    return {};
  }
  // Look-ahead grown by the distance off the path: a robot pushed off a tight arc (a car-like
  // robot lags its steering) still aims at a point ahead along the path, not abeam.
  const double lookahead = config_.lookahead + (point(cursor_) - q).norm();
  std::size_t j = cursor_;
  while (j < last && (point(j) - q).norm() < lookahead) ++j;
  const Eigen::Vector2d t = T_turn_base.inverse() * point(j);
  // Pure pursuit: the arc tangent to the heading through the look-ahead point.
  const double curvature = 2.0 * t.y() / std::max(t.squaredNorm(), 1e-6);
  if (t.x() < 0.0 && t.norm() > 0.1) {
    if (plan_.can_rotate) return {0.0, 0.0, (t.y() >= 0 ? 1.0 : -1.0) * config_.rotate_rate};
    // A car-like robot cannot rotate in place (a zero-speed yaw command leaves it standing for
    // ever): it backs up along the same arc until the point is ahead again (three-point turn).
    const double v = -config_.turn_speed;
    return {v, 0.0, v * curvature};
  }
  const double v = config_.turn_speed;
  return {v, 0.0, v * curvature};
}

ManoeuvreStep HeadlandManoeuvre::step(const core::Pose2& T_odom_base,
                                      const std::vector<Eigen::Vector2d>& ends) {
  ManoeuvreStep out;
  const core::Pose2 T_turn_base = T_odom_turn_.inverse() * T_odom_base;
  std::vector<Eigen::Vector2d> ends_turn;
  for (const auto& e : ends) ends_turn.push_back(T_odom_turn_.inverse() * e);
  const int passed_before = rows_passed_;
  const double target_before = target_y_;
  reanchor(ends_turn, T_turn_base.translation());
  out.row_passed = rows_passed_ > passed_before;
  out.reanchored = std::abs(target_y_ - target_before) > 0.02;
  for (int guard = 0; guard < 3 && !done(); ++guard) {
    Primitive& p = primitives_[index_];
    out.phase = p.headland ? ManoeuvrePhase::headland : ManoeuvrePhase::turning;
    if (p.rotate) {
      // Closed on odometry yaw (003 sec. II-B); the skid is corrected on the row ends later.
      const double err = core::angle_diff(p.heading, T_turn_base.theta);
      if (std::abs(err) < config_.heading_tolerance_deg * kPi / 180.0) {
        ++index_;
        continue;
      }
      const double w = std::clamp(2.0 * err, -config_.rotate_rate, config_.rotate_rate);
      out.cmd = {0.0, 0.0, std::abs(w) < 0.15 ? std::copysign(0.15, err) : w};
      return out;
    }
    const std::size_t before = index_;
    out.cmd = follow(p, T_turn_base);
    if (index_ == before) return out;
  }
  if (done()) out.phase = ManoeuvrePhase::done;
  return out;
}

}  // namespace rownav::navigate
