#include "rownav/detect/max_flow.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

namespace rownav::detect {
namespace {

struct TestEdge {
  int p, q;
  double cap, rev;
};
struct TestGraph {
  int n = 0;
  std::vector<double> source, sink;  // terminal capacities per node
  std::vector<TestEdge> edges;
};

/// n nodes, a chain plus random pairs (some opposite, some parallel), random terminals; integer
/// capacities when `integral`, so that flows are exact.
TestGraph random_graph(int n, std::uint64_t seed, bool integral) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto cap = [&] { return integral ? std::floor(u(rng) * 8.0) : u(rng); };
  TestGraph g;
  g.n = n;
  for (int i = 0; i < n; ++i) {
    const double r = u(rng);
    g.source.push_back(r < 0.35 ? cap() : 0.0);
    g.sink.push_back(r > 0.65 ? cap() : 0.0);
  }
  for (int i = 0; i + 1 < n; ++i) g.edges.push_back({i, i + 1, cap(), u(rng) < 0.5 ? cap() : 0.0});
  for (int k = 0; k < 2 * n; ++k) {
    const int p = static_cast<int>(u(rng) * n), q = static_cast<int>(u(rng) * n);
    if (p != q) g.edges.push_back({p, q, cap(), u(rng) < 0.3 ? cap() : 0.0});
  }
  return g;
}

/// The same graph through boost::boykov_kolmogorov_max_flow (the solver rownav used before):
/// flow and source side (black = source tree).
std::pair<double, std::vector<bool>> boost_cut(const TestGraph& tg) {
  using Graph = boost::compressed_sparse_row_graph<boost::directedS>;
  using Edge = boost::graph_traits<Graph>::edge_descriptor;
  struct Arc {
    std::size_t u, v;
    double cap;
  };
  std::vector<Arc> arcs;  // 2k and 2k + 1 are each other's reverse
  const auto add = [&](std::size_t a, std::size_t b, double c, double r) {
    arcs.push_back({a, b, c});
    arcs.push_back({b, a, r});
  };
  const auto n = static_cast<std::size_t>(tg.n), s = n, t = n + 1;
  for (std::size_t i = 0; i < n; ++i) {
    if (tg.source[i] > 0.0) add(s, i, tg.source[i], 0.0);
    if (tg.sink[i] > 0.0) add(i, t, tg.sink[i], 0.0);
  }
  for (const auto& e : tg.edges)
    add(static_cast<std::size_t>(e.p), static_cast<std::size_t>(e.q), e.cap, e.rev);
  std::vector<std::size_t> order(arcs.size()), pos(arcs.size());
  for (std::size_t k = 0; k < arcs.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return arcs[a].u < arcs[b].u; });
  std::vector<std::pair<std::size_t, std::size_t>> sorted;
  for (std::size_t k = 0; k < order.size(); ++k) {
    pos[order[k]] = k;
    sorted.emplace_back(arcs[order[k]].u, arcs[order[k]].v);
  }
  const Graph g(boost::edges_are_sorted, sorted.begin(), sorted.end(), n + 2);
  std::vector<double> cap(arcs.size()), res(arcs.size());
  std::vector<Edge> rev(arcs.size()), pred(n + 2);
  std::vector<boost::default_color_type> color(n + 2);
  std::vector<long> dist(n + 2);
  for (std::size_t k = 0; k < arcs.size(); ++k) {
    cap[pos[k]] = arcs[k].cap;
    rev[pos[k]] = Edge(arcs[k].v, pos[k ^ 1U]);
  }
  const auto ei = boost::get(boost::edge_index, g);
  const auto vi = boost::get(boost::vertex_index, g);
  const double flow = boost::boykov_kolmogorov_max_flow(
      g, boost::make_iterator_property_map(cap.begin(), ei),
      boost::make_iterator_property_map(res.begin(), ei),
      boost::make_iterator_property_map(rev.begin(), ei),
      boost::make_iterator_property_map(pred.begin(), vi),
      boost::make_iterator_property_map(color.begin(), vi),
      boost::make_iterator_property_map(dist.begin(), vi), vi, s, t);
  std::vector<bool> side(n);
  for (std::size_t i = 0; i < n; ++i) side[i] = color[i] == boost::black_color;
  return {flow, side};
}

std::pair<double, std::vector<bool>> rownav_cut(BkMaxFlow& mf, const TestGraph& tg) {
  mf.reset(tg.n);
  for (int i = 0; i < tg.n; ++i)
    mf.add_terminal(i, tg.source[static_cast<std::size_t>(i)],
                    tg.sink[static_cast<std::size_t>(i)]);
  for (const auto& e : tg.edges) mf.add_edge(e.p, e.q, e.cap, e.rev);
  const double flow = mf.solve();
  std::vector<bool> side(static_cast<std::size_t>(tg.n));
  for (int i = 0; i < tg.n; ++i) side[static_cast<std::size_t>(i)] = mf.source_side(i);
  return {flow, side};
}

/// Capacity of the cut (S = source_side) recomputed from the graph.
double cut_capacity(const TestGraph& tg, const std::vector<bool>& in_s) {
  double c = 0.0;
  for (int i = 0; i < tg.n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    c += in_s[ui] ? tg.sink[ui] : tg.source[ui];
  }
  for (const auto& e : tg.edges) {
    const bool sp = in_s[static_cast<std::size_t>(e.p)], sq = in_s[static_cast<std::size_t>(e.q)];
    if (sp && !sq) c += e.cap;
    if (sq && !sp) c += e.rev;
  }
  return c;
}

/// Nodes 0 and 1 with terminal capacities (source, sink) each and the arc 0 -> 1.
BkMaxFlow two_nodes(std::pair<double, double> t0, std::pair<double, double> t1, double cap01) {
  BkMaxFlow mf;
  mf.reset(2);
  mf.add_terminal(0, t0.first, t0.second);
  mf.add_terminal(1, t1.first, t1.second);
  mf.add_edge(0, 1, cap01, 0.0);
  return mf;
}

TEST(BkMaxFlow, TwoPathsOfKnownCapacity) {
  // s -> 0 (3), s -> 1 (2), 0 -> 1 (1), 0 -> t (2), 1 -> t (3): max flow 5, cut {s} | rest.
  BkMaxFlow mf = two_nodes({3.0, 2.0}, {2.0, 3.0}, 1.0);
  EXPECT_DOUBLE_EQ(mf.solve(), 5.0);
  EXPECT_FALSE(mf.source_side(0));
  EXPECT_FALSE(mf.source_side(1));
}

TEST(BkMaxFlow, FlowEqualsTheCutAndBoostsOnRandomGraphs) {
  BkMaxFlow mf;  // one instance: its kept buffers must not leak between graphs
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    const bool integral = seed % 2 == 0;
    const TestGraph tg = random_graph(5 + static_cast<int>(seed % 60), seed, integral);
    const auto [flow, side] = rownav_cut(mf, tg);
    const auto [bflow, bside] = boost_cut(tg);
    // Max-flow min-cut theorem: the cut found has the capacity of the flow pushed.
    EXPECT_NEAR(cut_capacity(tg, side), flow, 1e-9 * (1.0 + flow)) << "seed " << seed;
    EXPECT_NEAR(flow, bflow, 1e-9 * (1.0 + flow)) << "seed " << seed;
    // The smallest source side is unique; with exact (integer) flows it must be Boost's.
    if (integral) {
      EXPECT_EQ(side, bside) << "seed " << seed;
    }
  }
}

TEST(BkMaxFlow, SourceSideIsWhatTheSourceReachesInTheResidualGraph) {
  // s -> 0 (2), 0 -> 1 (1), 1 -> t (5): a flow of 1 saturates 0 -> 1 only; s still reaches
  // node 0 (1 left on s -> 0) and not node 1.
  BkMaxFlow mf = two_nodes({2.0, 0.0}, {0.0, 5.0}, 1.0);
  EXPECT_DOUBLE_EQ(mf.solve(), 1.0);
  EXPECT_TRUE(mf.source_side(0));
  EXPECT_FALSE(mf.source_side(1));
}

TEST(BkMaxFlow, NodesWithoutTerminalsOrArcsAreOnTheSinkSide) {
  BkMaxFlow mf;
  mf.reset(3);
  mf.add_terminal(0, 1.0, 0.0);
  EXPECT_DOUBLE_EQ(mf.solve(), 0.0);
  EXPECT_TRUE(mf.source_side(0));
  EXPECT_FALSE(mf.source_side(1));
  EXPECT_FALSE(mf.source_side(2));
}

}  // namespace
}  // namespace rownav::detect
