#include "rownav/detect/max_flow.hpp"

#include <algorithm>
#include <limits>

namespace rownav::detect {

void BkMaxFlow::reset(int num_nodes) {
  nodes_.assign(static_cast<std::size_t>(std::max(num_nodes, 0)), Node{});
  arcs_.clear();
  flow_ = 0.0;
}

void BkMaxFlow::add_terminal(int i, double from_source, double to_sink) {
  // Both terminal arcs carry min(from_source, to_sink) at once; the rest is one signed value.
  node(i).tr += from_source - to_sink;
  flow_ += std::min(from_source, to_sink);
}

void BkMaxFlow::add_edge(int p, int q, double cap, double rev_cap) {
  const int a = static_cast<int>(arcs_.size());
  Node& np = node(p);
  Node& nq = node(q);
  arcs_.push_back({q, np.first, cap});
  arcs_.push_back({p, nq.first, rev_cap});
  np.first = a;
  nq.first = a + 1;
}

void BkMaxFlow::activate(int i) {
  Node& n = node(i);
  if (n.active) return;
  n.active = true;
  queue_.push_back(i);
}

int BkMaxFlow::next_active() {
  while (queue_head_ < queue_.size()) {
    const int i = queue_[queue_head_++];
    if (node(i).parent != kFree) return i;  // stays active
    node(i).active = false;                 // left its tree since it was queued
  }
  queue_.clear();
  queue_head_ = 0;
  return -1;
}

int BkMaxFlow::grow(int i) {
  Node& ni = node(i);
  for (int a = ni.first; a >= 0; a = arc(a).next) {
    if (!(tree_residual(a, ni.sink) > 0.0)) continue;  // i's tree can grow along a
    const int j = arc(a).head;
    Node& nj = node(j);
    if (nj.parent == kFree) {
      nj.sink = ni.sink;
      nj.parent = a ^ 1;
      nj.ts = ni.ts;
      nj.dist = ni.dist + 1;
      activate(j);
    } else if (nj.sink != ni.sink) {
      return ni.sink ? a ^ 1 : a;  // the arc from the S side to the T side
    } else if (nj.ts <= ni.ts && nj.dist > ni.dist) {
      // Sec. 3.4: a shorter path to the terminal is taken when it is at least as fresh.
      nj.parent = a ^ 1;
      nj.ts = ni.ts;
      nj.dist = ni.dist + 1;
    }
  }
  return -1;
}

void BkMaxFlow::make_orphan(int i) {
  node(i).parent = kOrphan;
  orphans_.push_back(i);
}

void BkMaxFlow::augment(int middle) {
  // Bottleneck of the path source -> ... -> tail(middle) -> head(middle) -> ... -> sink.
  double b = arc(middle).r;
  int i = arc(middle ^ 1).head;
  for (int a = node(i).parent; a != kTerminal; a = node(i).parent) {
    b = std::min(b, arc(a ^ 1).r);
    i = arc(a).head;
  }
  b = std::min(b, node(i).tr);
  i = arc(middle).head;
  for (int a = node(i).parent; a != kTerminal; a = node(i).parent) {
    b = std::min(b, arc(a).r);
    i = arc(a).head;
  }
  b = std::min(b, -node(i).tr);
  // Push b; every arc (or terminal) it saturates cuts its child off: an orphan (sec. 3.2).
  arc(middle ^ 1).r += b;
  arc(middle).r -= b;
  i = arc(middle ^ 1).head;
  for (int a = node(i).parent; a != kTerminal; a = node(i).parent) {
    arc(a).r += b;
    arc(a ^ 1).r -= b;
    const int up = arc(a).head;
    if (arc(a ^ 1).r == 0.0) make_orphan(i);
    i = up;
  }
  node(i).tr -= b;
  if (node(i).tr == 0.0) make_orphan(i);
  i = arc(middle).head;
  for (int a = node(i).parent; a != kTerminal; a = node(i).parent) {
    arc(a ^ 1).r += b;
    arc(a).r -= b;
    const int up = arc(a).head;
    if (arc(a).r == 0.0) make_orphan(i);
    i = up;
  }
  node(i).tr += b;
  if (node(i).tr == 0.0) make_orphan(i);
  flow_ += b;
}

int BkMaxFlow::origin_distance(int j) {
  int d = 0;
  for (;;) {
    Node& n = node(j);
    if (n.ts == time_) return d + n.dist;
    ++d;
    if (n.parent == kTerminal) {
      n.ts = time_;
      n.dist = 1;
      return d;
    }
    if (n.parent == kOrphan) return -1;
    j = arc(n.parent).head;
  }
}

void BkMaxFlow::adopt_orphan(int i) {
  Node& ni = node(i);
  int best_arc = -1;
  int best_d = std::numeric_limits<int>::max();
  for (int a = ni.first; a >= 0; a = arc(a).next) {
    const int j = arc(a).head;
    const Node& nj = node(j);
    // j can be i's parent when the edge j -> i carries flow in their tree's direction.
    if (!(tree_residual(a ^ 1, ni.sink) > 0.0) || nj.sink != ni.sink || nj.parent == kFree)
      continue;
    // A valid parent has a path of parent arcs to the terminal (sec. 3.2 "origin").
    int d = origin_distance(j);
    if (d < 0) continue;
    if (d < best_d) {
      best_arc = a;
      best_d = d;
    }
    for (int k = j; node(k).ts != time_;) {  // sec. 3.4 marks
      Node& nk = node(k);
      nk.ts = time_;
      nk.dist = d--;
      k = arc(nk.parent).head;
    }
  }
  if (best_arc >= 0) {
    ni.parent = best_arc;
    ni.ts = time_;
    ni.dist = best_d + 1;
    return;
  }
  // No parent: i becomes free; its tree neighbours that can reach it become active and its
  // children orphans.
  ni.parent = kFree;
  for (int a = ni.first; a >= 0; a = arc(a).next) {
    const int j = arc(a).head;
    Node& nj = node(j);
    if (nj.sink != ni.sink || nj.parent == kFree) continue;
    if (tree_residual(a ^ 1, ni.sink) > 0.0) activate(j);
    if (nj.parent >= 0 && arc(nj.parent).head == i) make_orphan(j);
  }
}

void BkMaxFlow::adopt() {
  while (orphan_head_ < orphans_.size()) adopt_orphan(orphans_[orphan_head_++]);
  orphans_.clear();
  orphan_head_ = 0;
}

double BkMaxFlow::solve() {
  queue_.clear();
  queue_head_ = 0;
  orphans_.clear();
  orphan_head_ = 0;
  time_ = 0;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    Node& n = nodes_[i];
    n.active = false;
    n.ts = 0;
    n.dist = 1;
    n.parent = n.tr != 0.0 ? kTerminal : kFree;
    n.sink = n.tr < 0.0;
    if (n.parent == kTerminal) activate(static_cast<int>(i));
  }
  int current = -1;  // a node that closed a path is grown again before the queue moves on
  for (;;) {
    if (current >= 0 && node(current).parent == kFree) {
      node(current).active = false;
      current = -1;
    }
    const int i = current >= 0 ? current : next_active();
    if (i < 0) break;
    const int middle = grow(i);
    ++time_;
    if (middle < 0) {
      node(i).active = false;
      current = -1;
      continue;
    }
    current = i;
    augment(middle);
    adopt();
  }
  return flow_;
}

bool BkMaxFlow::source_side(int i) const {
  const Node& n = node(i);
  return n.parent != kFree && !n.sink;
}

}  // namespace rownav::detect
