#pragma once
// The one simultaneous descent of a probe BVH and a scene BVH that every pair
// query uses (collision, contact localisation, candidate lists, CCD). It is
// parameterised by
//   test(a, b, &key) -> bool   keep node pair (a, b)? key orders the visit
//                              (lower first) and is handed back to `alive`;
//                              on entry *key holds the parent pair's key (a
//                              child can only be as early as its parent);
//   alive(key) -> bool         is a popped pair still worth descending (CCD:
//                              its earliest contact is before the best so far);
//   on_leaf_pair(ip, is) -> bool   a surviving pair of leaves (node indices);
//                              false stops the descent. It may take the
//                              pair's key as a third argument.
// and an order (DescentOrder):
//   kDepthFirst  an explicit stack; each step pops one pair and pushes at
//                most two (one side split, the lower key on top), so the
//                stack never holds more than depth_P + depth_S + 1 entries.
//                A fixed array serves every BVH the builder makes (depth
//                <= about 3 log2(n) + 2, see bvh.cc); deeper trees (hand-made or
//                loaded) get a heap stack of the right size instead of an
//                overflow.
//   kBestFirst   the pending pair of lowest key over the whole descent first
//                (a binary heap on a fixed array). For a query that wants the
//                lowest-keyed leaf result (CCD: the first contact) it expands
//                only the pairs keyed below the answer, where depth-first also
//                expands those a deep dive reaches before the answer is known.
//                `alive` must be monotone (false for a key: false for every
//                larger one): the descent ends at the first popped pair that
//                is not alive. When the heap is full, a popped pair's subtree
//                is descended depth-first instead (same pairs, other order).
//                An optional stop() predicate, asked before each pair popped
//                from the heap, ends the descent early: the popped pair's
//                key is then a lower bound on the key of every leaf pair not
//                yet reached (bounded-time CCD: contact-free up to it).
// Both orders visit the same leaf pairs when alive is always true, and give
// a min-over-leaves query (CCD) the same answer. A descent can also leave
// its cut (every pair where it ended), and the next one start from that cut
// instead of the roots: descent_front.h.
#include <array>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "pd_core/proximity/bvh.h"

namespace pd {

// The kinds of pair query a solver spends its work on.
enum class QueryKind { kCollision, kLocalisation, kOutProjection, kListBuild };
inline constexpr int kNumQueryKinds = 4;

// Work done by proximity queries (cost accounting, benchmark reports).
struct ProximityCounters {
  int64_t box_tests = 0;       // node-pair bounding-volume tests
  int64_t triangle_tests = 0;  // triangle-pair tests
  // The same work (box + triangle tests) by the kind of query that did it
  // (see WorkScope), indexed by QueryKind.
  std::array<int64_t, kNumQueryKinds> by_kind{};
  int open_scopes = 0;  // WorkScope nesting depth
  int64_t total() const { return box_tests + triangle_tests; }
};

// Books the work done during its lifetime to `kind`, unless it runs inside
// another WorkScope of the same counters (a collision test's containment
// check belongs to the collision test).
class WorkScope {
 public:
  WorkScope(ProximityCounters* counters, QueryKind kind) : counters_(counters), kind_(kind) {
    if (counters_ && counters_->open_scopes++ == 0) start_ = counters_->total();
  }
  ~WorkScope() {
    if (counters_ && --counters_->open_scopes == 0)
      counters_->by_kind[static_cast<int>(kind_)] += counters_->total() - start_;
  }
  WorkScope(const WorkScope&) = delete;
  WorkScope& operator=(const WorkScope&) = delete;

 private:
  ProximityCounters* counters_;
  QueryKind kind_;
  int64_t start_ = 0;
};

enum class DescentOrder { kDepthFirst, kBestFirst };

namespace internal {

struct DescentEntry {
  int32_t ip, is;
  double key;
};

}  // namespace internal

// A node pair (probe BVH node, scene BVH node) by index.
struct NodePair {
  int32_t ip, is;
};

namespace internal {

// The node pairs, the caller's functions and the box-test count of one descent.
template <typename NodeTest, typename Alive, typename LeafFn>
struct Descent {
  const std::vector<BvhNode>& nodes_P;
  const std::vector<BvhNode>& nodes_S;
  NodeTest& test;
  Alive& alive;
  LeafFn& on_leaf_pair;
  int64_t tests = 0;
  // Optional: the descent's cut (see descent_front.h), every pair where
  // it ended: rejected by the test, a leaf pair reached, or left pending.
  std::vector<NodePair>* cut = nullptr;
  void Cut(const DescentEntry& e) {
    if (cut) cut->push_back({e.ip, e.is});
  }
  template <typename Entries>
  void CutAll(const Entries& entries, size_t n) {
    if (cut)
      for (size_t i = 0; i < n; ++i) cut->push_back({entries[i].ip, entries[i].is});
  }

  bool IsLeafPair(const DescentEntry& e) const {
    return nodes_P[e.ip].is_leaf() && nodes_S[e.is].is_leaf();
  }
  // The leaf action; false stops the descent.
  bool Leaf(const DescentEntry& e) {
    if constexpr (std::is_invocable_v<LeafFn&, int, int, double>)
      return on_leaf_pair(e.ip, e.is, e.key);
    else
      return on_leaf_pair(e.ip, e.is);
  }
  // Splits the larger node of internal pair e (or the one that is not a
  // leaf), tests both children against the other node and writes those
  // kept to child[]; returns how many. Of two, child[1] is to be visited
  // first: the lower key, the second child on a tie.
  int Expand(const DescentEntry& e, DescentEntry child[2]) {
    const BvhNode& a = nodes_P[e.ip];
    const BvhNode& b = nodes_S[e.is];
    const bool split_P = b.is_leaf() || (!a.is_leaf() && NodeSize2(a) >= NodeSize2(b));
    int n = 0;
    for (int c = 0; c < 2; ++c) {
      const int32_t ip = split_P ? (c == 0 ? e.ip + 1 : a.right_or_first) : e.ip;
      const int32_t is = split_P ? e.is : (c == 0 ? e.is + 1 : b.right_or_first);
      ++tests;
      double key = e.key;
      if (test(nodes_P[ip], nodes_S[is], &key))
        child[n++] = {ip, is, key};
      else
        Cut({ip, is, key});
    }
    if (n == 2 && child[0].key < child[1].key) std::swap(child[0], child[1]);
    return n;
  }
  // Depth-first over the kept pairs on stack[0, *top) until none is left
  // (true), the leaf action stops it (false), or pause(), asked after each
  // pair visited, says stop (true, the pairs still to visit left on the
  // stack: a call always makes progress). The stack holds at least the
  // depth of the subtree pairs.
  template <typename Stack, typename Pause>
  bool DepthFirst(Stack& stack, int* top, Pause&& pause) {
    while (*top > 0) {
      const DescentEntry e = stack[--*top];
      if (!alive(e.key)) {
        Cut(e);
        continue;
      }
      if (IsLeafPair(e)) {
        Cut(e);
        if (!Leaf(e)) {
          CutAll(stack, *top);
          return false;
        }
      } else {
        DescentEntry child[2];
        const int n = Expand(e, child);
        for (int c = 0; c < n; ++c) stack[(*top)++] = child[c];  // child[1] on top
      }
      if (*top > 0 && pause()) return true;
    }
    return true;
  }
  // Depth-first below `root` (a kept pair); false if the leaf action stopped it.
  template <typename Stack>
  bool DepthFirst(Stack& stack, const DescentEntry& root) {
    int top = 0;
    stack[top++] = root;
    return DepthFirst(stack, &top, [] { return false; });
  }
  // Best-first from `root` on a binary min-heap of the fixed array `heap`,
  // with `stack` for the depth-first fallback when the heap is full.
  // stop() asked before each pop; when it says stop, *stopped_at gets the
  // popped key and the descent returns true.
  template <size_t kHeap, typename Stack, typename Stop>
  bool BestFirst(std::array<DescentEntry, kHeap>& heap, Stack& stack, const DescentEntry& root,
                 Stop& stop, double* stopped_at) {
    return BestFirst(heap, stack, &root, 1, stop, stopped_at);
  }
  // The same from several kept pairs (a cut's) at once.
  template <size_t kHeap, typename Stack, typename Stop>
  bool BestFirst(std::array<DescentEntry, kHeap>& heap, Stack& stack, const DescentEntry* roots,
                 size_t num_roots, Stop& stop, double* stopped_at) {
    size_t size = 0;
    auto push = [&](const DescentEntry& x) {
      size_t i = size++;
      while (i > 0) {
        const size_t parent = (i - 1) / 2;
        if (!(x.key < heap[parent].key)) break;
        heap[i] = heap[parent];
        i = parent;
      }
      heap[i] = x;
    };
    auto pop = [&] {
      const DescentEntry top = heap[0];
      const DescentEntry last = heap[--size];
      size_t i = 0;
      for (;;) {
        size_t c = 2 * i + 1;
        if (c >= size) break;
        if (c + 1 < size && heap[c + 1].key < heap[c].key) ++c;
        if (!(heap[c].key < last.key)) break;
        heap[i] = heap[c];
        i = c;
      }
      if (size > 0) heap[i] = last;
      return top;
    };
    for (size_t r = 0; r < num_roots; ++r) {
      if (size + 1 <= kHeap) {
        push(roots[r]);
      } else if (!DepthFirst(stack, roots[r])) {  // more roots than the heap holds
        for (size_t k = r + 1; k < num_roots; ++k) Cut(roots[k]);
        CutAll(heap, size);
        return false;
      }
    }
    while (size > 0) {
      if (stop()) {
        *stopped_at = heap[0].key;  // the lowest pending key
        CutAll(heap, size);
        return true;
      }
      const DescentEntry e = pop();
      if (!alive(e.key)) {  // monotone: every pending pair is later
        Cut(e);
        CutAll(heap, size);
        return true;
      }
      if (IsLeafPair(e)) {
        Cut(e);
        if (!Leaf(e)) {
          CutAll(heap, size);
          return false;
        }
        continue;
      }
      if (size + 2 > kHeap) {
        if (!DepthFirst(stack, e)) {
          CutAll(heap, size);
          return false;
        }
        continue;
      }
      DescentEntry child[2];
      const int n = Expand(e, child);
      for (int c = 0; c < n; ++c) push(child[c]);
    }
    return true;
  }
};

}  // namespace internal

inline constexpr int kDescentStackCapacity = 192;

namespace internal {
// The caller's stop for a descent `d`, with d's box tests so far counted
// first (a work budget reads the counters; a descent counted them only when
// it ended).
template <typename D, typename Stop>
auto CountedStop(D& d, ProximityCounters* counters, Stop& stop) {
  return [&d, counters, &stop] {
    if (counters) counters->box_tests += std::exchange(d.tests, 0);
    return stop();
  };
}
}  // namespace internal
// Pending pairs a best-first descent holds before it falls back to
// depth-first for a popped pair's subtree (16 bytes each, on the stack).
inline constexpr int kBestFirstHeapCapacity = 1024;

namespace internal {
struct NeverStop {
  bool operator()() const { return false; }
};
// Calls run(stack) with a depth-first stack deep enough for the two
// hierarchies: a fixed array for every BVH the builder makes, else a heap
// vector of the right size.
template <typename Run>
void WithDescentStack(const Bvh& bvh_P, const Bvh& bvh_S, Run&& run) {
  const int needed = bvh_P.depth() + bvh_S.depth() + 1;
  if (needed <= kDescentStackCapacity) {
    std::array<DescentEntry, kDescentStackCapacity> stack;
    run(stack);
  } else {
    std::vector<DescentEntry> stack(needed);
    run(stack);
  }
}
}  // namespace internal

// Descends from the pair of subtrees rooted at nodes root_P and root_S (by
// default the whole hierarchies; a candidate list's entries are pairs of
// small subtrees, see candidate_pairs.h). Returns false if the leaf action
// stopped the descent. Best-first only: `stop` (see above) may end it early,
// with *stopped_at the lowest key pending (left untouched otherwise).
template <DescentOrder kOrder = DescentOrder::kDepthFirst, typename NodeTest, typename Alive,
          typename LeafFn, typename Stop = internal::NeverStop>
bool DescendBvhPair(const Bvh& bvh_P, const Bvh& bvh_S, NodeTest&& test, Alive&& alive,
                    LeafFn&& on_leaf_pair, ProximityCounters* counters = nullptr,
                    int32_t root_P = 0, int32_t root_S = 0, Stop&& stop = Stop{},
                    double* stopped_at = nullptr, std::vector<NodePair>* cut = nullptr) {
  static_assert(kOrder == DescentOrder::kBestFirst || std::is_same_v<std::decay_t<Stop>, internal::NeverStop>,
                "stop() is for best-first descents (a depth-first one pauses: DescentCursor)");
  if (bvh_P.empty() || bvh_S.empty()) return true;
  internal::Descent<std::remove_reference_t<NodeTest>, std::remove_reference_t<Alive>,
                    std::remove_reference_t<LeafFn>>
      d{bvh_P.nodes(), bvh_S.nodes(), test, alive, on_leaf_pair};
  d.tests = 1;
  d.cut = cut;
  auto counted_stop = internal::CountedStop(d, counters, stop);
  bool completed = true;
  // The root's parent key: the lowest there is.
  internal::DescentEntry root{root_P, root_S, -std::numeric_limits<double>::infinity()};
  if (!test(d.nodes_P[root_P], d.nodes_S[root_S], &root.key)) {
    d.Cut(root);
  } else {
    auto run = [&](auto& stack) {
      if constexpr (kOrder == DescentOrder::kBestFirst) {
        std::array<internal::DescentEntry, kBestFirstHeapCapacity> heap;
        double unused = 0.0;
        completed =
            d.BestFirst(heap, stack, root, counted_stop, stopped_at ? stopped_at : &unused);
      } else {
        completed = d.DepthFirst(stack, root);
      }
    };
    internal::WithDescentStack(bvh_P, bvh_S, run);
  }
  if (counters) counters->box_tests += d.tests;
  return completed;
}

// A depth-first descent (DescendBvhPair) done in pieces: a candidate list
// built in a real-time thread's idle time pauses when the next query is due
// and goes on after it. Holds the node pairs still to visit.
class DescentCursor {
 public:
  // Forgets any descent under way: the next ContinueBvhPairDescent starts
  // at the roots.
  void Reset() {
    started_ = false;
    top_ = 0;
  }
  bool started() const { return started_; }
  // True once the descent has visited every pair (or its leaf action stopped it).
  bool done() const { return started_ && top_ == 0; }

 private:
  template <typename NodeTest, typename LeafFn, typename Pause>
  friend bool ContinueBvhPairDescent(const Bvh&, const Bvh&, NodeTest&&, LeafFn&&, Pause&&,
                                     DescentCursor*, ProximityCounters*);
  std::vector<internal::DescentEntry> stack_;  // sized once per descent start
  int top_ = 0;
  bool started_ = false;
};

// DescendBvhPair<kDepthFirst> (alive always true) run in pieces: the first
// call after cursor->Reset() starts at the roots, later calls go on where
// the last one paused. pause() is asked after each node pair visited
// (expanded, or a leaf pair handed to on_leaf_pair) while pairs remain;
// the pairs visited, in order, and the box tests counted are those of one
// uninterrupted descent. Returns true once the descent is complete.
template <typename NodeTest, typename LeafFn, typename Pause>
bool ContinueBvhPairDescent(const Bvh& bvh_P, const Bvh& bvh_S, NodeTest&& test,
                            LeafFn&& on_leaf_pair, Pause&& pause, DescentCursor* cursor,
                            ProximityCounters* counters) {
  auto alive = [](double) { return true; };
  internal::Descent<std::remove_reference_t<NodeTest>, decltype(alive),
                    std::remove_reference_t<LeafFn>>
      d{bvh_P.nodes(), bvh_S.nodes(), test, alive, on_leaf_pair};
  if (!cursor->started_) {
    cursor->started_ = true;
    cursor->top_ = 0;
    if (bvh_P.empty() || bvh_S.empty()) return true;
    cursor->stack_.resize(bvh_P.depth() + bvh_S.depth() + 1);
    internal::DescentEntry root{0, 0, -std::numeric_limits<double>::infinity()};
    d.tests = 1;
    if (test(d.nodes_P[0], d.nodes_S[0], &root.key)) cursor->stack_[cursor->top_++] = root;
  }
  if (!d.DepthFirst(cursor->stack_, &cursor->top_, pause)) cursor->top_ = 0;  // stopped: done
  if (counters) counters->box_tests += d.tests;
  return cursor->top_ == 0;
}

// Calls fn(tp, ts) for every triangle pair of leaf nodes ip (probe) and is
// (scene); returns false as soon as fn does.
template <typename Fn>
bool ForEachTrianglePair(const Bvh& bvh_P, const Bvh& bvh_S, int ip, int is, Fn&& fn) {
  const BvhNode& a = bvh_P.nodes()[ip];
  const BvhNode& b = bvh_S.nodes()[is];
  for (int i = 0; i < a.count; ++i)
    for (int j = 0; j < b.count; ++j)
      if (!fn(bvh_P.order()[a.right_or_first + i], bvh_S.order()[b.right_or_first + j]))
        return false;
  return true;
}

}  // namespace pd
