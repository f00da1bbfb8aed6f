#pragma once
/// @file max_flow.hpp Minimum s-t cut by the Boykov-Kolmogorov max-flow algorithm (Boykov &
/// Kolmogorov 2004, "An experimental comparison of min-cut/max-flow algorithms for energy
/// minimization in vision", IEEE TPAMI 26(9), sec. 3), on flat arrays that are kept between
/// calls. Terminal capacities are stored on the nodes, as in the authors' own code.
///
/// rownav first used boost::boykov_kolmogorov_max_flow on a compressed_sparse_row_graph rebuilt
/// for every move; with it, RUBY took 3.0-3.3 ms per real corn frame against issue 11's 3 ms.
/// Building that graph and Boost's search were 62 % of the time; bench/max_flow_bench.cpp keeps
/// both solvers side by side (this one 1.6x faster on move-sized graphs).
#include <cstddef>
#include <vector>

namespace rownav::detect {

/// One s-t graph and its minimum cut. Not thread-safe; one instance per thread.
class BkMaxFlow {
 public:
  /// Removes every arc and makes `num_nodes` nodes with no terminal capacity (buffers kept).
  void reset(int num_nodes);

  /// Adds capacity `from_source` on source -> node i and `to_sink` on i -> sink (>= 0 each).
  void add_terminal(int i, double from_source, double to_sink);

  /// Adds the arcs p -> q with capacity `cap` and q -> p with capacity `rev_cap` (>= 0 each).
  void add_edge(int p, int q, double cap, double rev_cap);

  /// Pushes the maximum flow; returns its value.
  double solve();

  /// After solve(): true when node i is reachable from the source in the residual graph, i.e.
  /// on the source side of the minimum cut whose source side is smallest. That side does not
  /// depend on which maximum flow was found, so any exact max-flow solver gives the same cut.
  bool source_side(int i) const;

  int num_nodes() const { return static_cast<int>(nodes_.size()); }

 private:
  static constexpr int kFree = -1;      // in no search tree
  static constexpr int kTerminal = -2;  // parent is the source or the sink
  static constexpr int kOrphan = -3;    // lost its parent arc in the last augmentation

  struct Node {
    int first = -1;       // first outgoing arc
    int parent = kFree;   // arc to the parent in its tree, or kFree / kTerminal / kOrphan
    int ts = 0;           // time stamp of `dist` (the paper's distance heuristic, sec. 3.4)
    int dist = 0;         // distance to its terminal along parent arcs
    bool sink = false;    // in the sink tree T (else in S, when it has a parent)
    bool active = false;  // in the queue of active nodes, or the node being grown
    double tr = 0.0;      // residual terminal capacity: > 0 from the source, < 0 to the sink
  };
  struct Arc {
    int head = 0;    // arc 2k and 2k + 1 are each other's reverse
    int next = -1;   // next outgoing arc of the same tail
    double r = 0.0;  // residual capacity
  };

  Node& node(int i) { return nodes_[static_cast<std::size_t>(i)]; }
  const Node& node(int i) const { return nodes_[static_cast<std::size_t>(i)]; }
  Arc& arc(int a) { return arcs_[static_cast<std::size_t>(a)]; }
  /// Residual capacity of a tree edge tail(a) -> head(a), in the direction the tree grows: out
  /// of the source in S (arc a), into the sink in T (its reverse).
  double tree_residual(int a, bool sink) const {
    return arcs_[static_cast<std::size_t>(sink ? a ^ 1 : a)].r;
  }
  void activate(int i);
  int next_active();
  int grow(int i);  // sec. 3.2 growth stage: returns the arc S -> T that closes a path, or -1
  void augment(int middle);  // sec. 3.2 augmentation stage
  void make_orphan(int i);
  void adopt();  // sec. 3.2 adoption stage
  void adopt_orphan(int i);
  int origin_distance(int j);  // distance of j to its terminal, or -1 when it has none

  std::vector<Node> nodes_;
  std::vector<Arc> arcs_;
  std::vector<int> queue_;  // active nodes, FIFO from queue_head_
  std::size_t queue_head_ = 0;
  std::vector<int> orphans_;  // FIFO from orphan_head_
  std::size_t orphan_head_ = 0;
  int time_ = 0;
  double flow_ = 0.0;
};

}  // namespace rownav::detect
