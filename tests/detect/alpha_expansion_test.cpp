#include "rownav/detect/alpha_expansion.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

namespace rownav::detect {
namespace {

// A random tiny problem: n points, L labels, a chain plus a few random pairs.
LabelingProblem random_problem(int n, int labels, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  LabelingProblem pr;
  pr.num_points = n;
  pr.num_labels = labels;
  for (int i = 0; i < n * labels; ++i) pr.data_cost.push_back(u(rng));
  for (int p = 0; p + 1 < n; ++p) pr.edges.push_back({p, p + 1, 0.6 * u(rng)});
  for (int k = 0; k < n / 2; ++k) {
    const int p = static_cast<int>(u(rng) * n), q = static_cast<int>(u(rng) * n);
    if (p != q) pr.edges.push_back({std::min(p, q), std::max(p, q), 0.6 * u(rng)});
  }
  return pr;
}

double brute_force_optimum(const LabelingProblem& pr) {
  std::vector<int> f(static_cast<std::size_t>(pr.num_points), 0);
  double best = std::numeric_limits<double>::infinity();
  while (true) {
    best = std::min(best, labeling_energy(pr, f));
    std::size_t i = 0;
    while (i < f.size() && ++f[i] == pr.num_labels) f[i++] = 0;
    if (i == f.size()) break;
  }
  return best;
}

TEST(AlphaExpansion, ReachesWithinTwiceTheBruteForceOptimumAndNeverIncreases) {
  int exact = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const LabelingProblem pr = random_problem(7, 3, seed);
    const double opt = brute_force_optimum(pr);
    std::vector<int> f(7, 0);
    std::vector<double> trace;
    AlphaExpansion ae;
    const ExpansionStats st = ae.run(pr, f, 20, &trace);
    EXPECT_NEAR(st.energy, labeling_energy(pr, f), 1e-12);
    for (std::size_t i = 1; i < trace.size(); ++i) EXPECT_LT(trace[i], trace[i - 1]);
    EXPECT_GE(st.energy, opt - 1e-9);
    // Boykov-Veksler-Zabih 2001: for Potts, expansion's local minimum is within 2x the optimum.
    EXPECT_LE(st.energy, 2.0 * opt + 1e-9);
    exact += st.energy <= opt + 1e-9 ? 1 : 0;
  }
  // On such small problems expansion almost always finds the global optimum.
  EXPECT_GE(exact, 36);
}

TEST(AlphaExpansion, RunIsTheSweepOfSingleMovesOverEveryLabelUntilOneBringsNothing) {
  // Boykov, Veksler & Zabih 2001 Fig. 2, written out with expand(): the same labels and energy.
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    const LabelingProblem pr = random_problem(40, 6, seed);
    const int cycles = 1 + static_cast<int>(seed % 4);
    std::vector<int> ref(40, 0);
    AlphaExpansion single;
    double energy = labeling_energy(pr, ref);
    int sweeps = 0;
    for (int c = 0; c < cycles; ++c) {
      ++sweeps;
      bool improved = false;
      for (int alpha = 0; alpha < pr.num_labels; ++alpha)
        improved = single.expand(pr, alpha, ref, energy) || improved;
      if (!improved) break;
    }
    std::vector<int> f(40, 0);
    AlphaExpansion ae;
    const ExpansionStats st = ae.run(pr, f, cycles);
    EXPECT_EQ(f, ref) << "seed " << seed;
    EXPECT_EQ(st.energy, energy) << "seed " << seed;
    EXPECT_EQ(st.cycles, sweeps) << "seed " << seed;
    EXPECT_EQ(st.max_flow_calls, st.cycles * pr.num_labels) << "seed " << seed;
  }
}

TEST(AlphaExpansion, SingleMoveIsTheOptimalBinaryMove) {
  // 6 points, 3 labels: the expansion move for alpha must equal the best of all 2^6 moves.
  for (std::uint64_t seed = 100; seed < 130; ++seed) {
    const LabelingProblem pr = random_problem(6, 3, seed);
    std::vector<int> f{0, 1, 2, 0, 1, 2};
    for (int alpha = 0; alpha < 3; ++alpha) {
      double best = std::numeric_limits<double>::infinity();
      for (int mask = 0; mask < 64; ++mask) {
        std::vector<int> g = f;
        for (int i = 0; i < 6; ++i)
          if (mask & (1 << i)) g[static_cast<std::size_t>(i)] = alpha;
        best = std::min(best, labeling_energy(pr, g));
      }
      std::vector<int> g = f;
      double e = labeling_energy(pr, g);
      AlphaExpansion ae;
      ae.expand(pr, alpha, g, e);
      EXPECT_NEAR(e, best, 1e-9) << "seed " << seed << " alpha " << alpha;
    }
  }
}

TEST(AlphaExpansion, SmoothnessOverridesNoisyDataCosts) {
  // A chain whose data slightly prefers alternating labels; strong Potts weights make it uniform.
  LabelingProblem pr;
  pr.num_points = 8;
  pr.num_labels = 2;
  for (int p = 0; p < 8; ++p) {
    pr.data_cost.push_back(p % 2 == 0 ? 0.0 : 0.2);
    pr.data_cost.push_back(p % 2 == 0 ? 0.2 : 0.0);
  }
  for (int p = 0; p + 1 < 8; ++p) pr.edges.push_back({p, p + 1, 1.0});
  std::vector<int> f{0, 1, 0, 1, 0, 1, 0, 1};
  AlphaExpansion ae;
  ae.run(pr, f);
  for (const int l : f) EXPECT_EQ(l, f[0]);
}

// Two close rows (0.35 m apart) of plants, each plant a blob of points (sigma 8 cm, centres
// jittered across by +-8 cm): nearest-line assignment splits the blobs that straddle the
// midline; the Potts term of Malavazi 2018 eq. (1) keeps each plant on one row.
TEST(AlphaExpansion, GraphCutBeatsNearestLineAssignmentOnCloseRows) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> blob(0.0, 0.08);
  std::uniform_real_distribution<double> jitter(-0.08, 0.08);
  std::vector<Eigen::Vector2d> pts;
  std::vector<int> truth;  // 1 = row y = 0, 2 = row y = 0.35
  for (int row = 0; row < 2; ++row)
    for (double x = 0.2 * row; x < 6.0; x += 0.4) {
      const double yc = 0.35 * row + jitter(rng);
      for (int k = 0; k < 12; ++k) {
        pts.emplace_back(x + 0.5 * blob(rng), yc + blob(rng));
        truth.push_back(row + 1);
      }
    }
  LabelingProblem pr;
  pr.num_points = static_cast<int>(pts.size());
  pr.num_labels = 3;  // L_0, row 0, row 1
  for (const auto& p : pts) {
    pr.data_cost.push_back(0.3);              // outlier
    pr.data_cost.push_back(std::abs(p.y()));  // |p - L_1|
    pr.data_cost.push_back(std::abs(p.y() - 0.35));
  }
  const double lambda = 0.15, zeta = 0.1;  // eq. (1), (2)
  for (int p = 0; p < pr.num_points; ++p)
    for (int q = p + 1; q < pr.num_points; ++q) {
      const double d2 =
          (pts[static_cast<std::size_t>(p)] - pts[static_cast<std::size_t>(q)]).squaredNorm();
      if (d2 < 0.15 * 0.15) pr.edges.push_back({p, q, lambda * std::exp(-d2 / (zeta * zeta))});
    }
  std::vector<int> nearest(pts.size());
  for (int p = 0; p < pr.num_points; ++p) {
    int best = 0;
    for (int l = 1; l < 3; ++l)
      if (pr.cost(p, l) < pr.cost(p, best)) best = l;
    nearest[static_cast<std::size_t>(p)] = best;
  }
  std::vector<int> cut = nearest;
  AlphaExpansion ae;
  const ExpansionStats st = ae.run(pr, cut);
  const auto correct = [&](const std::vector<int>& f) {
    int c = 0;
    for (std::size_t i = 0; i < f.size(); ++i) c += f[i] == truth[i] ? 1 : 0;
    return c;
  };
  int changed = 0;
  for (std::size_t i = 0; i < cut.size(); ++i) changed += cut[i] != nearest[i] ? 1 : 0;
  std::printf(
      "close rows: %zu points, nearest %d correct (E %.2f), graph cut %d correct (E %.2f), "
      "%d labels changed\n",
      pts.size(), correct(nearest), labeling_energy(pr, nearest), correct(cut), st.energy, changed);
  EXPECT_GT(changed, 0);
  EXPECT_LT(st.energy, labeling_energy(pr, nearest));
  EXPECT_GT(correct(cut), correct(nearest));
}

}  // namespace
}  // namespace rownav::detect
