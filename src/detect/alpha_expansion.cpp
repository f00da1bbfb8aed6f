#include "rownav/detect/alpha_expansion.hpp"

#include <cmath>

#include "rownav/detect/max_flow.hpp"

namespace rownav::detect {

namespace {

double potts(int a, int b, double w) {
  return a == b ? 0.0 : w;
}

}  // namespace

double labeling_energy(const LabelingProblem& problem, std::span<const int> labels) {
  double e = 0.0;
  for (int p = 0; p < problem.num_points; ++p)
    e += problem.cost(p, labels[static_cast<std::size_t>(p)]);
  for (const auto& ed : problem.edges)
    e +=
        potts(labels[static_cast<std::size_t>(ed.p)], labels[static_cast<std::size_t>(ed.q)], ed.w);
  return e;
}

struct AlphaExpansion::Impl {
  std::vector<int> node_of;            // point -> graph node, -1 when the point's move is fixed
  std::vector<int> point_of;           // graph node -> point
  std::vector<double> unary;           // per node: cost(switch) - cost(keep)
  std::vector<double> incident;        // per point: sum of incident Potts weights
  std::vector<std::size_t> adj_first;  // per point: its pairs in adj (CSR)
  std::vector<std::pair<int, double>> adj;  // (neighbour, w)
  std::vector<int> proposal;
  BkMaxFlow graph;  // the move's graph: node i = point point_of[i]

  /// Selects the points whose binary move is free. A point p with f_p == alpha is fixed; so is a
  /// point for which switching costs more than all its Potts weights can repay
  /// (D_p(alpha) - D_p(f_p) > sum_q w_pq): keeping is then optimal in every minimiser, so
  /// dropping it from the graph keeps the move exact.
  void select_nodes(const LabelingProblem& pr, int alpha, const std::vector<int>& f) {
    const auto n = static_cast<std::size_t>(pr.num_points);
    node_of.assign(n, -1);
    point_of.clear();
    for (std::size_t p = 0; p < n; ++p) {
      const int ip = static_cast<int>(p);
      if (f[p] == alpha) continue;
      if (pr.cost(ip, alpha) - pr.cost(ip, f[p]) > incident[p]) continue;
      node_of[p] = static_cast<int>(point_of.size());
      point_of.push_back(ip);
    }
  }

  /// Per-point adjacency of the Potts pairs and their weight sums (once per problem).
  void prepare(const LabelingProblem& pr) {
    const auto n = static_cast<std::size_t>(pr.num_points);
    incident.assign(n, 0.0);
    adj_first.assign(n + 1, 0);
    for (const auto& e : pr.edges) {
      ++adj_first[static_cast<std::size_t>(e.p) + 1];
      ++adj_first[static_cast<std::size_t>(e.q) + 1];
    }
    for (std::size_t p = 0; p < n; ++p) adj_first[p + 1] += adj_first[p];
    adj.resize(adj_first[n]);
    std::vector<std::size_t> fill(adj_first.begin(), adj_first.end() - 1);
    for (const auto& e : pr.edges) {
      const auto p = static_cast<std::size_t>(e.p), q = static_cast<std::size_t>(e.q);
      adj[fill[p]++] = {e.q, e.w};
      adj[fill[q]++] = {e.p, e.w};
      incident[p] += e.w;
      incident[q] += e.w;
    }
  }

  /// Energy change of switching the points of `proposal` that differ from `f` (unary + pairs
  /// touching a changed point, each pair once).
  double move_delta(const LabelingProblem& pr, const std::vector<int>& f) const {
    double d = 0.0;
    for (const int p : point_of) {
      const auto up = static_cast<std::size_t>(p);
      if (proposal[up] == f[up]) continue;
      d += pr.cost(p, proposal[up]) - pr.cost(p, f[up]);
      for (std::size_t k = adj_first[up]; k < adj_first[up + 1]; ++k) {
        const auto [q, w] = adj[k];
        const auto uq = static_cast<std::size_t>(q);
        if (proposal[uq] != f[uq] && q < p) continue;  // counted from q
        d += potts(proposal[up], proposal[uq], w) - potts(f[up], f[uq], w);
      }
    }
    return d;
  }

  /// Kolmogorov & Zabih 2004 construction of the move energy; x = 1 means "switch to alpha",
  /// node on the sink side.
  void build(const LabelingProblem& pr, int alpha, const std::vector<int>& f) {
    const auto m = static_cast<int>(point_of.size());
    graph.reset(m);
    unary.assign(static_cast<std::size_t>(m), 0.0);
    for (int i = 0; i < m; ++i) {
      const int p = point_of[static_cast<std::size_t>(i)];
      unary[static_cast<std::size_t>(i)] =
          pr.cost(p, alpha) - pr.cost(p, f[static_cast<std::size_t>(p)]);
    }
    for (int np = 0; np < m; ++np) {
      const int p = point_of[static_cast<std::size_t>(np)];
      const int fp = f[static_cast<std::size_t>(p)];
      for (std::size_t k = adj_first[static_cast<std::size_t>(p)];
           k < adj_first[static_cast<std::size_t>(p) + 1]; ++k) {
        const auto [q, w] = adj[k];
        const int nq = node_of[static_cast<std::size_t>(q)];
        const int fq = f[static_cast<std::size_t>(q)];
        if (nq < 0) {  // q fixed at its current label
          unary[static_cast<std::size_t>(np)] += potts(alpha, fq, w) - potts(fp, fq, w);
          continue;
        }
        if (q < p) continue;  // the pair is added once, from its lower point
        // E00 = V(fp,fq), E01 = V(fp,a), E10 = V(a,fq), E11 = 0; submodular for a metric V.
        const double a = potts(fp, fq, w), b = potts(fp, alpha, w), c = potts(alpha, fq, w);
        unary[static_cast<std::size_t>(np)] += c - a;
        unary[static_cast<std::size_t>(nq)] += 0.0 - c;
        const double cap = b + c - a;
        if (cap > 0.0) graph.add_edge(np, nq, cap, 0.0);
      }
    }
    for (int i = 0; i < m; ++i) {
      const double u = unary[static_cast<std::size_t>(i)];
      if (u > 0.0)
        graph.add_terminal(i, u, 0.0);  // paid when i goes to the sink (switch)
      else if (u < 0.0)
        graph.add_terminal(i, 0.0, -u);  // paid when i stays at the source (keep)
    }
  }
};

AlphaExpansion::AlphaExpansion() : impl_(std::make_unique<Impl>()) {}
AlphaExpansion::~AlphaExpansion() = default;

bool AlphaExpansion::expand(const LabelingProblem& problem, int alpha, std::vector<int>& labels,
                            double& energy) {
  impl_->prepare(problem);
  return expand_prepared(problem, alpha, labels, energy);
}

bool AlphaExpansion::expand_prepared(const LabelingProblem& problem, int alpha,
                                     std::vector<int>& labels, double& energy) {
  Impl& im = *impl_;
  im.select_nodes(problem, alpha, labels);
  if (im.point_of.empty()) return false;
  const auto m = im.point_of.size();
  im.build(problem, alpha, labels);
  im.graph.solve();
  im.proposal = labels;
  bool any = false;
  for (std::size_t i = 0; i < m; ++i) {
    // Source side (reachable from the source) = keep; the rest = switch: a minimum cut.
    if (im.graph.source_side(static_cast<int>(i))) continue;
    im.proposal[static_cast<std::size_t>(im.point_of[i])] = alpha;
    any = true;
  }
  if (!any) return false;
  const double e = energy + im.move_delta(problem, labels);
  if (!(e < energy - 1e-12 * (1.0 + std::abs(energy)))) return false;
  labels.swap(im.proposal);
  energy = e;
  return true;
}

ExpansionStats AlphaExpansion::run(const LabelingProblem& problem, std::vector<int>& labels,
                                   int max_cycles, std::vector<double>* trace) {
  ExpansionStats st;
  labels.resize(static_cast<std::size_t>(problem.num_points), 0);
  for (auto& l : labels)
    if (l < 0 || l >= problem.num_labels) l = 0;
  st.energy = labeling_energy(problem, labels);
  impl_->prepare(problem);
  if (trace) trace->push_back(st.energy);
  for (int c = 0; c < max_cycles; ++c) {
    ++st.cycles;
    bool improved = false;
    for (int alpha = 0; alpha < problem.num_labels; ++alpha) {
      ++st.max_flow_calls;
      if (!expand_prepared(problem, alpha, labels, st.energy)) continue;
      improved = true;
      ++st.moves;
      if (trace) trace->push_back(st.energy);
    }
    if (!improved) break;
  }
  return st;
}

}  // namespace rownav::detect
