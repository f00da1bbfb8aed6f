#pragma once
/// @file alpha_expansion.hpp Multi-label energy minimisation by alpha-expansion (Boykov, Veksler
/// & Zabih 2001) with Potts smoothness, each binary move solved exactly as a min cut by
/// BkMaxFlow (max_flow.hpp; graph construction of Kolmogorov & Zabih 2004). Used by
/// PEARL / OPAL / RUBY (Malavazi 2018 sec. 2.1.2 step 2); public so that it can be tested alone.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace rownav::detect {

/// A labelling problem: E(f) = sum_p D_p(f_p) + sum_{(p,q)} w_pq [f_p != f_q]
/// (Malavazi 2018 eq. (1) / (4) once the data costs hold the distances and the outlier cost, and
/// w_pq already includes lambda).
struct LabelingProblem {
  int num_points = 0;
  int num_labels = 0;
  std::vector<double> data_cost;  ///< num_points * num_labels, row-major: D_p(l) = [p * L + l]
  struct Edge {
    int p = 0;
    int q = 0;
    double w = 0.0;  ///< >= 0, Potts weight of the pair (each unordered pair once)
  };
  std::vector<Edge> edges;

  double cost(int p, int l) const {
    return data_cost[static_cast<std::size_t>(p * num_labels + l)];
  }
};

/// Energy of a labelling (labels.size() == num_points, each in [0, num_labels)).
double labeling_energy(const LabelingProblem& problem, std::span<const int> labels);

/// Statistics of one alpha-expansion run.
struct ExpansionStats {
  int cycles = 0;  ///< sweeps over all labels
  int moves = 0;   ///< expansion moves that lowered the energy
  int max_flow_calls = 0;
  double energy = 0.0;  ///< final energy
};

/// Alpha-expansion solver. Keeps its buffers between calls (one instance per thread).
class AlphaExpansion {
 public:
  AlphaExpansion();
  ~AlphaExpansion();
  AlphaExpansion(const AlphaExpansion&) = delete;
  AlphaExpansion& operator=(const AlphaExpansion&) = delete;

  /// Improves `labels` in place: sweeps every label alpha, solves the binary "keep or switch to
  /// alpha" move by min cut, accepts it when it lowers the energy, until a sweep brings no
  /// decrease or `max_cycles` sweeps. The energy never increases. `trace`, when given, receives
  /// the energy before the first move and after every accepted move.
  ExpansionStats run(const LabelingProblem& problem, std::vector<int>& labels, int max_cycles = 10,
                     std::vector<double>* trace = nullptr);

  /// Solves one expansion move for `alpha`; returns true (and updates labels) when it lowers the
  /// energy `energy` (updated too).
  bool expand(const LabelingProblem& problem, int alpha, std::vector<int>& labels, double& energy);

 private:
  bool expand_prepared(const LabelingProblem& problem, int alpha, std::vector<int>& labels,
                       double& energy);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rownav::detect
