// Headland manoeuvres: the chosen turn kind's primitives (navigate/turn_planner.hpp) driven on
// the odometry pose (rotations, pure pursuit) and re-anchored on the row ends seen.
#include "rownav/navigate/headland_manoeuvre.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "rownav/core/angle.hpp"
#include "rownav/navigate/turn_path.hpp"
#include "rownav/track/row_geometry.hpp"

namespace rownav::navigate {

namespace {

constexpr double kPi = std::numbers::pi;

struct WeightedEnd {
  double y, weight;  // [m] across the rows, frames seen
};

// Residual of y from the lattice a + k s (k whole).
double off_lattice(double y, double a, double s) {
  const double k = std::round((y - a) / s);
  return std::abs(y - a - k * s);
}

// How well the lattice a + k s explains the row ends: each end on it (within gate x s) adds its
// weight, the closer the more; each end off it between the lattice's first and last end, and
// each lattice point there with no end, takes `penalty` x (its, a mean end's) weight away. A
// half spacing puts every end on its lattice but leaves every other point empty; a double one
// leaves every other end off it: either scores below zero from four ends on.
double lattice_score(const std::vector<WeightedEnd>& ends, double a, double s, double gate,
                     double penalty) {
  double score = 0.0, mean = 0.0, k_min = 1e9, k_max = -1e9;
  std::vector<long> on;
  for (const auto& e : ends) {
    mean += e.weight / static_cast<double>(ends.size());
    const double r = off_lattice(e.y, a, s);
    if (r >= gate * s) continue;
    const long k = std::lround((e.y - a) / s);
    on.push_back(k);
    k_min = std::min(k_min, double(k)), k_max = std::max(k_max, double(k));
    score += e.weight * (1.0 - r / (gate * s));
  }
  for (const auto& e : ends) {
    const double k = (e.y - a) / s;
    if (off_lattice(e.y, a, s) >= gate * s && k > k_min && k < k_max) score -= penalty * e.weight;
  }
  std::sort(on.begin(), on.end());
  on.erase(std::unique(on.begin(), on.end()), on.end());
  if (!on.empty())
    score -= penalty * mean * static_cast<double>(on.back() - on.front() + 1 - long(on.size()));
  return score;
}

// The row ends' spacing as the lattice that best explains them (lattice_score, the ends weighted
// by the frames each was seen in). The candidates are every difference of two row ends divided
// by 1-3 (rows missing between them) within [lo, hi]; the winner is refined by least squares
// over its row ends. A thing on the row-end line between two rows, or an end seen across the
// robot with its nearest-point bias, lies off the lattice, where a median of neighbour
// differences took the two halves of a split spacing for two spacings (zoo:1:61). nullopt: no
// lattice scores above zero, or under min_ends on it.
std::optional<double> lattice_spacing(const std::vector<WeightedEnd>& ends, double lo, double hi,
                                      double gate, double penalty, int min_ends) {
  double best = 0.0, best_s = 0.0, best_a = 0.0;
  for (std::size_t i = 0; i < ends.size(); ++i)
    for (std::size_t j = i + 1; j < ends.size(); ++j)
      for (int k = 1; k <= 3; ++k) {
        const double c = std::abs(ends[i].y - ends[j].y) / k;
        if (!(c > lo && c < hi)) continue;
        const double score = lattice_score(ends, ends[i].y, c, gate, penalty);
        if (score > best) best = score, best_s = c, best_a = ends[i].y;
      }
  if (!(best > 0.0)) return std::nullopt;
  // The median over neighbouring ends on the lattice of their difference per spacing: the one
  // across the robot carries the nearest-point bias of both ends, the median leaves it out.
  std::vector<std::pair<double, double>> on;  // (k, y)
  for (const auto& e : ends)
    if (off_lattice(e.y, best_a, best_s) < gate * best_s)
      on.emplace_back(std::round((e.y - best_a) / best_s), e.y);
  if (static_cast<int>(on.size()) < min_ends) return std::nullopt;
  std::sort(on.begin(), on.end());
  std::vector<double> d;
  for (std::size_t i = 1; i < on.size(); ++i)
    if (on[i].first > on[i - 1].first)
      d.push_back((on[i].second - on[i - 1].second) / (on[i].first - on[i - 1].first));
  if (d.empty()) return best_s;
  std::sort(d.begin(), d.end());
  const std::size_t n = d.size();
  const double s = n % 2 ? d[n / 2] : 0.5 * (d[n / 2 - 1] + d[n / 2]);
  return s > lo && s < hi ? s : best_s;
}

}  // namespace

void ManoeuvreConfig::validate() const {
  core::check_positive(turn_speed, "turn_speed");
  core::check_positive(rotate_rate, "rotate_rate");
  core::check_range(heading_tolerance_deg, 0.1, 20.0, "heading_tolerance_deg");
  core::check_positive(lookahead, "lookahead");
  core::check_range(anchor_gate, 0.05, 0.5, "anchor_gate");
  core::check_positive(pole_band, "pole_band");
  core::check_range(spacing_poles, 2, 1000, "spacing_poles");
  core::check_range(spacing_tolerance, 0.0, 1.0, "spacing_tolerance");
  core::check_range(spacing_tolerance_long, 0.0, 1.0, "spacing_tolerance_long");
  core::check_range(pole_share, 0.0, 1.0, "pole_share");
  core::check_range(lattice_gate, 0.01, 0.5, "lattice_gate");
  core::check_non_negative(lattice_penalty, "lattice_penalty");
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
  TurnGeometry g;
  g.exit_x = e;
  g.shift = shift_;
  g.side = side_;
  g.spacing = spacing_;
  g.radius = plan.radius;
  primitives_ = make_turn_planner(plan.kind)->plan(g);
  for (auto& p : primitives_)
    if (!p.rotate) densify_turn_path(p.path, p.anchor);
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

double HeadlandManoeuvre::planned_distance() const {
  double d = 0.0;
  for (const auto& p : primitives_)
    for (std::size_t i = 1; i < p.path.size(); ++i) d += (p.path[i] - p.path[i - 1]).norm();
  return d;
}

double HeadlandManoeuvre::planned_time() const {
  double rotation = 0.0, heading = 0.0;  // the turn frame starts along the exit direction
  for (const auto& p : primitives_)
    if (p.rotate) {
      rotation += std::abs(core::angle_diff(p.heading, heading));
      heading = p.heading;
    }
  return planned_distance() / config_.turn_speed + rotation / config_.rotate_rate;
}

void HeadlandManoeuvre::reanchor(const std::vector<Eigen::Vector2d>& ends_turn,
                                 const Eigen::Vector2d& robot) {
  // Row ends near the row-end line, merged over the frames (odometry keeps them put).
  for (const auto& q : ends_turn) {
    if (!q.allFinite() || std::abs(q.x()) > config_.pole_band) continue;
    // One row end per anchor gate: a canopy seen from the headland gives end estimates spread
    // across its width (crowns, a vine's foliage); two rows are a spacing apart.
    const double merge = config_.anchor_gate * spacing_;
    auto it = std::min_element(poles_.begin(), poles_.end(), [&](const Pole& a, const Pole& b) {
      return std::abs(a.y - q.y()) < std::abs(b.y - q.y());
    });
    if (it == poles_.end() || std::abs(it->y - q.y()) >= merge) {
      poles_.push_back({q.y(), 1});
    } else {
      it->y = (it->y * it->n + q.y()) / (it->n + 1);
      most_seen_ = std::max(most_seen_, ++it->n);
    }
  }
  // Rows passed abeam: the row ends between the exit corridor and the robot (003 sec. II-C).
  int passed = 0;
  for (const auto& p : poles_)
    if (side_ * p.y > 0.0 && side_ * p.y < side_ * robot.y()) ++passed;
  rows_passed_ = std::max(rows_passed_, passed);
  // The target corridor lies between the two row ends that flank its centre, `shift` row ends'
  // spacings out: counted with the row ends' own spacing, an in-row spacing 15 % short would
  // miss the far flank by half a gate for shift 1 and by more for each row skipped.
  const double s = pole_spacing(), expected = side_ * shift_ * s, gate = config_.anchor_gate * s;
  // Each flank is the row end nearest its expected place (a weed or a post inside the gate
  // must not take a row's place because it was listed later).
  const auto nearest = [&](double y) -> std::optional<double> {
    std::optional<double> best;
    for (const auto& p : poles_)
      if (counted(p) && std::abs(p.y - y) < gate &&
          (!best || std::abs(p.y - y) < std::abs(*best - y)))
        best = p.y;
    return best;
  };
  const std::optional<double> lo = nearest(expected - s / 2.0), hi = nearest(expected + s / 2.0);
  // Only abeam of the target: its two flanking row ends are then on either side of the robot and
  // the bias of each end's nearest point towards the robot cancels in the midpoint.
  if (lo && hi && std::abs(robot.y() - target_y_) < 0.5 * s) target_y_ = (*lo + *hi) / 2.0;
}

bool HeadlandManoeuvre::counted(const Pole& p) const {
  return p.n >= 2 && p.n >= config_.pole_share * most_seen_;
}

double HeadlandManoeuvre::pole_spacing() const {
  std::vector<WeightedEnd> ends;
  for (const auto& p : poles_)
    if (counted(p)) ends.push_back({p.y, static_cast<double>(p.n)});
  if (static_cast<int>(ends.size()) < config_.spacing_poles) return spacing_;
  const double shortest = spacing_ / (1.0 + config_.spacing_tolerance);
  const double longest = spacing_ * (1.0 + config_.spacing_tolerance_long);
  return lattice_spacing(ends, shortest, longest, config_.lattice_gate, config_.lattice_penalty,
                         config_.spacing_poles)
      .value_or(spacing_);
}

core::Twist2 HeadlandManoeuvre::follow(const TurnPrimitive& p, const core::Pose2& T_turn_base) {
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
    const TurnPrimitive& p = primitives_[index_];
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
