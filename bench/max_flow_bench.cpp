/// @file max_flow_bench.cpp The max-flow solver of every alpha-expansion move (RUBY / OPAL /
/// PEARL): rownav's BkMaxFlow beside Boost's boykov_kolmogorov_max_flow on a
/// compressed_sparse_row_graph (what AlphaExpansion used until 2026-12-06), each building the
/// graph and cutting it, on the same seeded move-sized graphs. One core.
///   ./build/max_flow_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <random>
#include <vector>

#include "rownav/detect/max_flow.hpp"

namespace {

using namespace rownav;

/// A move-sized s-t graph (sizes of RUBY's moves on corn_rows_2d: a few hundred nodes, about
/// three pairs a node, a third of the nodes tied to each terminal), seeded.
struct MoveGraph {
  struct Arc {
    std::size_t u, v;
    double cap;
  };
  std::size_t n = 0;
  std::vector<Arc> arcs;  // 2k and 2k + 1 are each other's reverse; n = source, n + 1 = sink
};
MoveGraph move_graph(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  MoveGraph g;
  g.n = n;
  const auto add = [&](std::size_t a, std::size_t b, double c) {
    g.arcs.push_back({a, b, c});
    g.arcs.push_back({b, a, 0.0});
  };
  for (std::size_t i = 0; i < n; ++i) {
    const double r = u(rng);
    if (r < 0.33) add(n, i, u(rng));
    if (r > 0.67) add(i, n + 1, u(rng));
    for (int k = 0; k < 3; ++k) {
      const auto j = std::min(n - 1, i + 1 + static_cast<std::size_t>(u(rng) * 12.0));
      if (j != i) add(i, j, 0.5 * u(rng));
    }
  }
  return g;
}

/// rownav's BkMaxFlow, graph built each time as AlphaExpansion does for every move.
void BM_MaxFlowRownav(benchmark::State& state) {
  const MoveGraph g = move_graph(static_cast<std::size_t>(state.range(0)), 1);
  detect::BkMaxFlow mf;
  for (auto _ : state) {
    mf.reset(static_cast<int>(g.n));
    for (std::size_t k = 0; k < g.arcs.size(); k += 2) {
      const auto& a = g.arcs[k];
      if (a.u == g.n)
        mf.add_terminal(static_cast<int>(a.v), a.cap, 0.0);
      else if (a.v == g.n + 1)
        mf.add_terminal(static_cast<int>(a.u), 0.0, a.cap);
      else
        mf.add_edge(static_cast<int>(a.u), static_cast<int>(a.v), a.cap, 0.0);
    }
    benchmark::DoNotOptimize(mf.solve());
  }
}

/// boost::boykov_kolmogorov_max_flow on a compressed_sparse_row_graph, graph built each time:
/// what AlphaExpansion did until 2026-12-06.
void BM_MaxFlowBoost(benchmark::State& state) {
  using Graph = boost::compressed_sparse_row_graph<boost::directedS>;
  using Edge = boost::graph_traits<Graph>::edge_descriptor;
  const MoveGraph g = move_graph(static_cast<std::size_t>(state.range(0)), 1);
  const std::size_t nv = g.n + 2, na = g.arcs.size();
  std::vector<std::size_t> first(nv + 1), pos(na);
  std::vector<std::pair<std::size_t, std::size_t>> sorted(na);
  std::vector<double> cap(na), res(na);
  std::vector<Edge> rev(na), pred(nv);
  std::vector<boost::default_color_type> color(nv);
  std::vector<long> dist(nv);
  for (auto _ : state) {
    std::fill(first.begin(), first.end(), 0);
    for (const auto& a : g.arcs) ++first[a.u + 1];
    for (std::size_t i = 0; i < nv; ++i) first[i + 1] += first[i];
    for (std::size_t k = 0; k < na; ++k) {
      pos[k] = first[g.arcs[k].u]++;
      sorted[pos[k]] = {g.arcs[k].u, g.arcs[k].v};
    }
    for (std::size_t k = 0; k < na; ++k) {
      cap[pos[k]] = g.arcs[k].cap;
      rev[pos[k]] = Edge(g.arcs[k].v, pos[k ^ 1U]);
    }
    std::fill(res.begin(), res.end(), 0.0);
    std::fill(color.begin(), color.end(), boost::white_color);
    std::fill(dist.begin(), dist.end(), 0);
    const Graph graph(boost::edges_are_sorted, sorted.begin(), sorted.end(), nv);
    const auto ei = boost::get(boost::edge_index, graph);
    const auto vi = boost::get(boost::vertex_index, graph);
    benchmark::DoNotOptimize(boost::boykov_kolmogorov_max_flow(
        graph, boost::make_iterator_property_map(cap.begin(), ei),
        boost::make_iterator_property_map(res.begin(), ei),
        boost::make_iterator_property_map(rev.begin(), ei),
        boost::make_iterator_property_map(pred.begin(), vi),
        boost::make_iterator_property_map(color.begin(), vi),
        boost::make_iterator_property_map(dist.begin(), vi), vi, g.n, g.n + 1));
  }
}

BENCHMARK(BM_MaxFlowRownav)->Arg(50)->Arg(300)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MaxFlowBoost)->Arg(50)->Arg(300)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
