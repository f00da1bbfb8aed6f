#include "rownav/detect/alpha_expansion.hpp"

// GCC 12 reports a false -Wmaybe-uninitialized inside Boost.Graph's edge iterators once they are
// inlined into expand(); the suppression covers this file only.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#include <cmath>

namespace rownav::detect {

namespace {

using Traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;

struct VertexProps {
  Traits::edge_descriptor pred;
  boost::default_color_type color = boost::white_color;
  long dist = 0;
};

struct EdgeProps {
  double cap = 0.0;
  double res = 0.0;
  Traits::edge_descriptor rev;
};

using Graph =
    boost::adjacency_list<boost::vecS, boost::vecS, boost::directedS, VertexProps, EdgeProps>;

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
  std::vector<int> node_of;      // point -> graph node, -1 when the point's move is fixed
  std::vector<int> point_of;     // graph node -> point
  std::vector<double> unary;     // per node: cost(switch) - cost(keep)
  std::vector<double> incident;  // per point: sum of incident Potts weights
  std::vector<int> proposal;
  Graph graph;  // reused: vertices kept, out-edge lists cleared between moves

  /// Empties the graph's edges and makes sure it has at least n vertices.
  Graph& reset_graph(std::size_t n) {
    for (std::size_t v = 0; v < boost::num_vertices(graph); ++v) boost::clear_out_edges(v, graph);
    while (boost::num_vertices(graph) < n) boost::add_vertex(graph);
    return graph;
  }

  void add_pair(Graph& g, int u, int v, double cap_uv, double cap_vu) {
    const auto e =
        boost::add_edge(static_cast<std::size_t>(u), static_cast<std::size_t>(v), g).first;
    const auto r =
        boost::add_edge(static_cast<std::size_t>(v), static_cast<std::size_t>(u), g).first;
    g[e].cap = cap_uv;
    g[r].cap = cap_vu;
    g[e].rev = r;
    g[r].rev = e;
  }

  /// Selects the points whose binary move is free. A point p with f_p == alpha is fixed; so is a
  /// point for which switching costs more than all its Potts weights can repay
  /// (D_p(alpha) - D_p(f_p) > sum_q w_pq): keeping is then optimal in every minimiser, so
  /// dropping it from the graph keeps the move exact.
  void select_nodes(const LabelingProblem& pr, int alpha, const std::vector<int>& f) {
    const auto n = static_cast<std::size_t>(pr.num_points);
    incident.assign(n, 0.0);
    for (const auto& e : pr.edges) {
      incident[static_cast<std::size_t>(e.p)] += e.w;
      incident[static_cast<std::size_t>(e.q)] += e.w;
    }
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

  /// Kolmogorov & Zabih 2004 construction of the move energy; x = 1 means "switch to alpha",
  /// node on the sink side. Returns the graph with source = m, sink = m + 1.
  void build(const LabelingProblem& pr, int alpha, const std::vector<int>& f, Graph& g) {
    const auto m = static_cast<int>(point_of.size());
    unary.assign(static_cast<std::size_t>(m), 0.0);
    for (int i = 0; i < m; ++i) {
      const int p = point_of[static_cast<std::size_t>(i)];
      unary[static_cast<std::size_t>(i)] =
          pr.cost(p, alpha) - pr.cost(p, f[static_cast<std::size_t>(p)]);
    }
    for (const auto& e : pr.edges) {
      const int np = node_of[static_cast<std::size_t>(e.p)],
                nq = node_of[static_cast<std::size_t>(e.q)];
      if (np < 0 && nq < 0) continue;
      const int fp = f[static_cast<std::size_t>(e.p)], fq = f[static_cast<std::size_t>(e.q)];
      if (np < 0 || nq < 0) {  // one end fixed at its current label
        const int free_node = np < 0 ? nq : np;
        const int fixed_label = np < 0 ? fp : fq, free_label = np < 0 ? fq : fp;
        unary[static_cast<std::size_t>(free_node)] +=
            potts(alpha, fixed_label, e.w) - potts(free_label, fixed_label, e.w);
        continue;
      }
      // E00 = V(fp,fq), E01 = V(fp,a), E10 = V(a,fq), E11 = 0; submodular for a metric V.
      const double a = potts(fp, fq, e.w), b = potts(fp, alpha, e.w), c = potts(alpha, fq, e.w);
      unary[static_cast<std::size_t>(np)] += c - a;
      unary[static_cast<std::size_t>(nq)] += 0.0 - c;
      const double cap = b + c - a;
      if (cap > 0.0) add_pair(g, np, nq, cap, 0.0);
    }
    const int s = m, t = m + 1;
    for (int i = 0; i < m; ++i) {
      const double u = unary[static_cast<std::size_t>(i)];
      if (u > 0.0)
        add_pair(g, s, i, u, 0.0);  // paid when i goes to the sink (switch)
      else if (u < 0.0)
        add_pair(g, i, t, -u, 0.0);  // paid when i stays at the source (keep)
    }
  }
};

AlphaExpansion::AlphaExpansion() : impl_(std::make_unique<Impl>()) {}
AlphaExpansion::~AlphaExpansion() = default;

bool AlphaExpansion::expand(const LabelingProblem& problem, int alpha, std::vector<int>& labels,
                            double& energy) {
  Impl& im = *impl_;
  im.select_nodes(problem, alpha, labels);
  if (im.point_of.empty()) return false;
  const auto m = im.point_of.size();
  Graph& g = im.reset_graph(m + 2);
  im.build(problem, alpha, labels, g);
  boost::boykov_kolmogorov_max_flow(
      g, boost::get(&EdgeProps::cap, g), boost::get(&EdgeProps::res, g),
      boost::get(&EdgeProps::rev, g), boost::get(&VertexProps::pred, g),
      boost::get(&VertexProps::color, g), boost::get(&VertexProps::dist, g),
      boost::get(boost::vertex_index, g), m, m + 1);
  im.proposal = labels;
  bool any = false;
  for (std::size_t i = 0; i < m; ++i) {
    // Source tree (black) = keep; sink tree and free nodes = switch: both are minimum cuts.
    if (g[i].color == boost::black_color) continue;
    im.proposal[static_cast<std::size_t>(im.point_of[i])] = alpha;
    any = true;
  }
  if (!any) return false;
  const double e = labeling_energy(problem, im.proposal);
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
  if (trace) trace->push_back(st.energy);
  for (int c = 0; c < max_cycles; ++c) {
    ++st.cycles;
    bool improved = false;
    for (int alpha = 0; alpha < problem.num_labels; ++alpha) {
      ++st.max_flow_calls;
      if (!expand(problem, alpha, labels, st.energy)) continue;
      improved = true;
      ++st.moves;
      if (trace) trace->push_back(st.energy);
    }
    if (!improved) break;
  }
  return st;
}

}  // namespace rownav::detect
