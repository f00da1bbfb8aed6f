// Emmi 2021 Table 4 on simulated fields: a scripted serpentine path through every lane of B1 /
// V1 (bench/map_fields.hpp), a planar scanner (lms_1081) ray cast against the field mesh, the
// truth labeller (sim/truth_labeller.hpp) and map::PlaceEstimator on perfect odometry. Reports
// per-frame state accuracy against the true place (outside a band around the true transitions),
// the transition detection success rate (DSR), the key locations' mean distance error (MDE) and
// orthogonal error (Orth_E). Not a Google Benchmark: own main.
//   build/map_bench [seeds] [false_positive_rate] [false_negative_rate] [v: list transitions]
//                   [labels: truth | blind | camera] [n: a neighbouring field of another crop]
//                   [a: then drive the alley beside the last row, 0.75 m from it]
// Issue 12's camera: `camera` labels the points by the simulated camera (every 5th frame),
// excess-green boxes and vision::CameraLabeller (B1 only: the paper's vineyard detector sees
// trunks, the excess-green one the canopy); `blind` is the truth labeller without the target
// region (every crop is the target crop: a labeller that cannot tell crops apart). With `n`, a
// second B1 field (another seed) lies 1.5 m beyond the target's last row, its plants drawn in the
// camera's other-crop colour and `other_crop` for the truth labeller.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "map_fields.hpp"
#include "rownav/map/place_estimator.hpp"
#include "rownav/sim/field_truth.hpp"
#include "rownav/sim/lidar.hpp"
#include "rownav/sim/lidar_presets.hpp"
#include "rownav/sim/ray_caster.hpp"
#include "rownav/sim/pinhole_camera.hpp"
#include "rownav/sim/truth_labeller.hpp"
#include "rownav/vision/camera_labeller.hpp"
#include "rownav/vision/excess_green_detector.hpp"

namespace {

using rownav::core::Pose2;
namespace map = rownav::map;
namespace sim = rownav::sim;

constexpr double kFrameStep = 0.05;   // [m] travel between frames (0.5 m/s at 10 Hz)
constexpr double kLeadIn = 2.5;       // [m] start before the first lane
constexpr double kTurnOut = 1.0;      // [m] straight beyond a row end before the U-turn
constexpr double kBand = 0.5;         // [m] accuracy excludes this around true transitions
constexpr double kMatchRadius = 1.0;  // [m] a validated transition this close matches a true one
constexpr double kNeighbourGap = 1.5;  // [m] target's last row to the neighbour's first
bool g_alley = false;  // 7th argument "a": the alley pass after the serpentine

void straight(std::vector<Pose2>& out, Eigen::Vector2d a, Eigen::Vector2d b) {
  const Eigen::Vector2d d = b - a;
  const int n = std::max(1, static_cast<int>(d.norm() / kFrameStep));
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d p = a + d * (double(k) / n);
    out.emplace_back(p.x(), p.y(), std::atan2(d.y(), d.x()));
  }
}

void u_turn(std::vector<Pose2>& out, Eigen::Vector2d from, Eigen::Vector2d to, Eigen::Vector2d t) {
  const Eigen::Vector2d c = 0.5 * (from + to);
  const double r = 0.5 * (to - from).norm();
  const Eigen::Vector2d s = (from - c) / r;
  const double turn = (t.x() * s.y() - t.y() * s.x()) > 0.0 ? -1.0 : 1.0;  // towards `to`
  const int n = std::max(2, static_cast<int>(M_PI * r / kFrameStep));
  for (int k = 0; k < n; ++k) {
    const double a = turn * M_PI * k / n;
    const Eigen::Vector2d p = c + Eigen::Rotation2Dd(a) * (from - c);
    out.emplace_back(p.x(), p.y(), std::atan2(t.y(), t.x()) + a);
  }
}

/// Serpentine through every corridor of the first block.
std::vector<Pose2> serpentine(const sim::FieldTruth& truth) {
  std::vector<Pose2> out;
  const int block = truth.blocks().front();
  for (int k = 0; k < truth.corridor_count(block); ++k) {
    auto c = truth.corridor_centre(block, k);
    if (k % 2) std::reverse(c.begin(), c.end());
    const Eigen::Vector2d t = (c.back() - c.front()).normalized();
    const Eigen::Vector2d a = c.front() - (k == 0 ? kLeadIn : 0.0) * t, b = c.back() + kTurnOut * t;
    if (k > 0) straight(out, c.front() - kTurnOut * t, c.front());
    straight(out, k == 0 ? a : c.front(), b);
    if (k + 1 < truth.corridor_count(block)) {
      auto n = truth.corridor_centre(block, k + 1);
      if (k % 2 == 0) std::reverse(n.begin(), n.end());
      u_turn(out, b, n.front() - kTurnOut * t * -1.0, t);
    }
  }
  return out;
}

/// From the serpentine's last pose: a U-turn into the alley beside the last row (half the
/// neighbour gap from it: between the field and its neighbour) and along it past the row end.
void alley_pass(std::vector<Pose2>& out, const sim::Field& field) {
  const auto& row = field.rows.back().polyline;  // rows ordered by y: the last is beside the alley
  const Eigen::Vector2d off(0.0, 0.5 * kNeighbourGap);
  const Pose2 end = out.back();
  const Eigen::Vector2d t(std::cos(end.theta), std::sin(end.theta));
  const Eigen::Vector2d from = end.translation();
  const bool forward = t.x() < 0.0;  // heading back to x = 0: the alley is driven towards +x
  const Eigen::Vector2d a = (forward ? row.front() : row.back()) + off;
  const Eigen::Vector2d b = (forward ? row.back() : row.front()) + off;
  const Eigen::Vector2d entry(from.x(), a.y());
  u_turn(out, from, entry, t);
  straight(out, entry, b - kTurnOut * t);
}

int place_index(sim::Place p) { return p == sim::Place::lane ? 1 : p == sim::Place::alley ? 2 : 0; }

struct TrueTransition {
  Eigen::Vector2d at;   // robot position
  int to = 0;           // 0 headland, 1 lane, 2 alley
  Eigen::Vector2d key, tangent;  // corridor centre at the row end and its direction
};

struct Metrics {
  double accuracy = 0, dsr = 0, mde = 0, orth = 0;
  int true_transitions = 0, detected = 0, false_transitions = 0;
};

/// The corridor end nearest to p, with the corridor direction.
std::pair<Eigen::Vector2d, Eigen::Vector2d> nearest_end(const sim::FieldTruth& truth,
                                                        const Eigen::Vector2d& p) {
  std::pair<Eigen::Vector2d, Eigen::Vector2d> best;
  double bd = 1e300;
  const int block = truth.blocks().front();
  for (int k = 0; k < truth.corridor_count(block); ++k) {
    const auto& c = truth.corridor_centre(block, k);
    const Eigen::Vector2d t = (c.back() - c.front()).normalized();
    for (const auto& e : {c.front(), c.back()})
      if ((e - p).norm() < bd) bd = (e - p).norm(), best = {e, t};
  }
  if (g_alley) {  // the alley's ends: half a lane width beyond the last row (Emmi 2021 eq. 2-3)
    const auto& row = truth.field().rows.back().polyline;
    const Eigen::Vector2d t = (row.back() - row.front()).normalized();
    const Eigen::Vector2d off(0.0, 0.5 * truth.field().row_spacing);
    for (const auto& e : {Eigen::Vector2d(row.front() + off), Eigen::Vector2d(row.back() + off)})
      if ((e - p).norm() < bd) bd = (e - p).norm(), best = {e, t};
  }
  return best;
}

bool g_verbose = false;  // 4th argument "v": every true and validated transition
enum class Labels { truth, blind, camera };
Labels g_labels = Labels::truth;  // 5th argument
bool g_neighbour = false;         // 6th argument "n"
constexpr int kCameraEvery = 5;        // frames per camera image (0.25 m of travel)
int g_debug_frames = 60;  // ... and the first frames whose filtered place is wrong

/// One mission: poses, true and validated places, true transitions, the estimator's map.
struct Mission {
  std::vector<Pose2> poses;
  std::vector<int> true_place, est_place;
  std::vector<TrueTransition> truths;
  std::vector<map::MapTransition> validated;
};

/// Base-frame points and surface classes of one planar scan (flat ground, level scanner).
void scan_points(const rownav::core::Scan2D& scan, const std::vector<sim::SurfaceClass>& beam,
                 const Eigen::Vector3d& mount, std::vector<Eigen::Vector3f>& pts,
                 std::vector<sim::SurfaceClass>& classes) {
  pts.clear();
  classes.clear();
  for (std::size_t b = 0; b < scan.ranges.size(); ++b) {
    if (!scan.valid(b)) continue;
    const double a = scan.angle(b), r = scan.ranges[b];
    pts.emplace_back(float(mount.x() + r * std::cos(a)), float(r * std::sin(a)), float(mount.z()));
    classes.push_back(beam[b]);
  }
}

map::PlaceEstimatorConfig estimator_config(const sim::Field& field, double eps) {
  map::PlaceEstimatorConfig pc;
  pc.key_locations.lane_width = field.row_spacing;
  pc.key_locations.max_distance = field.headland_width;
  pc.clusters.eps = eps;
  return pc;
}

/// The world mesh: the field, and with g_neighbour a second one (another seed) beyond it; the
/// target region (world x, y) of the field's own plants into lo / hi.
sim::TriangleMesh world_mesh(const rownav::bench_map::MapField& f, const sim::Field& field,
                             Eigen::Vector2d& lo, Eigen::Vector2d& hi) {
  sim::TriangleMesh mesh = field.mesh;
  const Eigen::AlignedBox2d rows = field.row_bounds();
  lo = rows.min() - Eigen::Vector2d(100.0, 0.5 * kNeighbourGap);
  hi = rows.max() + Eigen::Vector2d(100.0, 0.5 * kNeighbourGap);
  if (!g_neighbour) return mesh;
  auto other = f.config;
  other.seed += 1000;
  const float dy = float(rows.max().y() - rows.min().y() + kNeighbourGap);
  mesh.append(sim::generate_field(other).mesh,
              Eigen::Isometry3f(Eigen::Translation3f(0.0f, dy, 0.0f)));
  return mesh;
}

/// The camera chain of issue 12 (Emmi 2021 Fig. 2b).
struct CameraChain {
  CameraChain(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, std::uint64_t seed)
      : camera(config(lo, hi), seed) {}
  static sim::PinholeCameraConfig config(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
    sim::PinholeCameraConfig c;
    c.use_target_region = true;
    c.target_min = lo;
    c.target_max = hi;
    return c;
  }
  sim::PinholeCamera camera;
  rownav::vision::ExcessGreenDetector detector;
  rownav::vision::CameraLabeller labeller;
};

Mission simulate(const rownav::bench_map::MapField& f, std::uint64_t seed, double fp, double fn) {
  const sim::Field field = sim::generate_field(f.config);
  const sim::FieldTruth truth(field);
  Eigen::Vector2d lo, hi;
  const sim::RayCaster world(world_mesh(f, field, lo, hi));
  CameraChain cam(lo, hi, seed + 2);
  sim::LidarConfig lc = sim::lidar_preset("lms_1081");
  lc.mount_xyz = {0.3, 0.0, f.scanner_height};
  lc.motion_during_sweep = false;
  sim::Lidar lidar(lc, seed);
  sim::TruthLabellerConfig tc;
  tc.false_positive_rate = fp;
  tc.false_negative_rate = fn;
  tc.use_target_region = g_neighbour && g_labels == Labels::truth;  // as before without one
  tc.target_min = lo;
  tc.target_max = hi;
  sim::TruthLabeller labeller(tc, seed + 1);
  map::PlaceEstimator est(estimator_config(field, f.dbscan_eps));
  Mission m;
  m.poses = serpentine(truth);
  if (g_alley) alley_pass(m.poses, field);
  std::vector<Eigen::Vector3f> pts;
  std::vector<sim::SurfaceClass> classes, beam;
  std::vector<map::PointLabel> labels;
  for (std::size_t i = 0; i < m.poses.size(); ++i) {
    const Pose2& T = m.poses[i];
    const double stamp = 0.1 * static_cast<double>(i);
    const Eigen::Isometry3d iso = T.to_isometry();
    scan_points(lidar.scan(world, [&](double) { return iso; }, stamp, &beam), beam, lc.mount_xyz,
                pts, classes);
    if (g_labels == Labels::camera) {
      if (i % kCameraEvery == 0) cam.labeller.set_image(cam.camera.render(world, iso, stamp), cam.detector);
      cam.labeller.label(pts, labels);
    } else {
      labeller.set_frame(T, classes);
      labeller.label(pts, labels);
    }
    const map::PlaceEstimate pe = est.update(pts, labels, T, stamp);
    m.est_place.push_back(map::filtered_index(pe.place));
    m.true_place.push_back(place_index(truth.at(T, stamp, 0.0).place));
    if (g_verbose && map::filtered_index(pe.filtered) != m.true_place.back() && g_debug_frames-- > 0)
      std::printf("frame %zu (%.2f, %.2f) true %d filtered %d inst %d c %.2f %.2f %.2f rows %d\n",
                  i, T.x, T.y, m.true_place.back(), map::filtered_index(pe.filtered),
                  map::filtered_index(pe.instantaneous), pe.c_index[0], pe.c_index[1],
                  pe.c_index[2], pe.rows);
    if (i > 0 && m.true_place[i] != m.true_place[i - 1]) {
      const auto [key, tangent] = nearest_end(truth, T.translation());
      m.truths.push_back({T.translation(), m.true_place[i], key, tangent});
    }
  }
  m.validated = est.map().transitions();
  return m;
}

void print_transitions(const Mission& m) {
  for (const auto& t : m.truths) std::printf("true  -> %d at (%.2f, %.2f)\n", t.to, t.at.x(), t.at.y());
  for (const auto& v : m.validated) {
    const Eigen::Vector2d at = (m.poses.front() * v.T_field_base).translation();
    const Eigen::Vector2d k = m.poses.front() * v.key.p;
    std::printf("valid %s -> %s at (%.2f, %.2f) key (%.2f, %.2f)\n",
                std::string(rownav::core::enum_name(v.from)).c_str(),
                std::string(rownav::core::enum_name(v.to)).c_str(), at.x(), at.y(), k.x(), k.y());
  }
}

double state_accuracy(const Mission& m) {
  int n = 0, ok = 0;
  for (std::size_t i = 0; i < m.poses.size(); ++i) {
    bool near = false;
    for (const auto& t : m.truths) near = near || (m.poses[i].translation() - t.at).norm() < kBand;
    if (near) continue;
    ++n;
    ok += m.est_place[i] == m.true_place[i] ? 1 : 0;
  }
  return n ? double(ok) / n : 0.0;
}

Metrics score(const Mission& mission) {
  Metrics m;
  m.accuracy = state_accuracy(mission);
  const Pose2 T_world_field = mission.poses.front();  // F_f: the first pose
  std::vector<bool> used(mission.validated.size(), false);
  for (const auto& t : mission.truths) {
    for (std::size_t j = 0; j < used.size(); ++j) {
      const auto& v = mission.validated[j];
      const Eigen::Vector2d at = (T_world_field * v.T_field_base).translation();
      if (used[j] || map::filtered_index(v.to) != t.to || (at - t.at).norm() > kMatchRadius)
        continue;
      used[j] = true;
      const Eigen::Vector2d e = T_world_field * v.key.p - t.key;
      m.mde += e.norm();
      m.orth += std::abs(t.tangent.x() * e.y() - t.tangent.y() * e.x());
      ++m.detected;
      break;
    }
  }
  m.true_transitions = static_cast<int>(mission.truths.size());
  m.false_transitions = static_cast<int>(std::count(used.begin(), used.end(), false));
  m.dsr = mission.truths.empty() ? 0.0 : double(m.detected) / double(mission.truths.size());
  if (m.detected) m.mde /= m.detected, m.orth /= m.detected;
  return m;
}

Metrics run(const rownav::bench_map::MapField& f, std::uint64_t seed, double fp, double fn) {
  const Mission m = simulate(f, seed, fp, fn);
  if (g_verbose) print_transitions(m);
  return score(m);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 3;
  const double fp = argc > 2 ? std::atof(argv[2]) : 0.01;
  const double fn = argc > 3 ? std::atof(argv[3]) : 0.1;
  g_verbose = argc > 4 && argv[4][0] == 'v';
  const std::string labels = argc > 5 ? argv[5] : "truth";
  g_labels = labels == "camera" ? Labels::camera : labels == "blind" ? Labels::blind : Labels::truth;
  g_neighbour = argc > 6 && argv[6][0] == 'n';
  g_alley = argc > 7 && argv[7][0] == 'a';
  std::printf("| field | seed | frames acc. | DSR | true / detected / false | MDE [m] | Orth_E [m] |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const auto& mk : {rownav::bench_map::field_b1, rownav::bench_map::field_v1}) {
    if ((g_labels == Labels::camera || g_alley) && mk == rownav::bench_map::field_v1)
      continue;  // B1 only
    std::vector<double> acc, dsr, mde, orth;
    std::string name;
    for (int s = 1; s <= seeds; ++s) {
      const auto f = mk(static_cast<std::uint64_t>(s));
      name = f.name;
      const Metrics m = run(f, static_cast<std::uint64_t>(s), fp, fn);
      std::printf("| %s | %d | %.4f | %.3f | %d / %d / %d | %.3f | %.3f |\n", f.name.c_str(), s,
                  m.accuracy, m.dsr, m.true_transitions, m.detected, m.false_transitions, m.mde,
                  m.orth);
      std::fflush(stdout);
      acc.push_back(m.accuracy), dsr.push_back(m.dsr), mde.push_back(m.mde), orth.push_back(m.orth);
    }
    std::printf("| %s | median | %.4f | %.3f | | %.3f | %.3f |\n", name.c_str(), median(acc),
                median(dsr), median(mde), median(orth));
  }
  return 0;
}
