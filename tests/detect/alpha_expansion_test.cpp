#include "rownav/detect/alpha_expansion.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace rownav::detect
