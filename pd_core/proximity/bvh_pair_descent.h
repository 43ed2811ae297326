#pragma once
// The one simultaneous descent of a probe BVH and a scene BVH that every pair
// query uses (collision, contact localisation, candidate lists, CCD). It is
// parameterised by
//   test(a, b, &key) -> bool   keep node pair (a, b)? key orders the children
//                              (lower first) and is handed back to `alive`;
//   alive(key) -> bool         is a popped pair still worth descending (CCD:
//                              its earliest contact is before the best so far);
//   on_leaf_pair(ip, is) -> bool   a surviving pair of leaves (node indices);
//                              false stops the descent. It may take the
//                              pair's key as a third argument.
// Depth-first on an explicit stack: each step pops one pair and pushes at
// most two, descending one side, so the stack never holds more than
// depth_P + depth_S + 1 entries. A fixed array serves every BVH the builder
// makes (median split: depth <= log2(n) + 2); deeper trees (hand-made or
// loaded) get a heap stack of the right size instead of an overflow.
#include <array>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "pd_core/proximity/bvh.h"

namespace pd {

// Work done by proximity queries (cost accounting, benchmark reports).
struct ProximityCounters {
  int64_t box_tests = 0;       // node-pair bounding-volume tests
  int64_t triangle_tests = 0;  // triangle-pair tests
};

namespace internal {

struct DescentEntry {
  int32_t ip, is;
  double key;
};

template <typename Stack, typename NodeTest, typename Alive, typename LeafFn>
void DescendWithStack(Stack& stack, const Bvh& bvh_P, const Bvh& bvh_S, NodeTest& test,
                      Alive& alive, LeafFn& on_leaf_pair, ProximityCounters* counters) {
  const auto& nodes_P = bvh_P.nodes();
  const auto& nodes_S = bvh_S.nodes();
  int64_t tests = 1;
  double key = 0.0;
  int top = 0;
  if (test(nodes_P[0], nodes_S[0], &key)) stack[top++] = {0, 0, key};
  while (top > 0) {
    const DescentEntry e = stack[--top];
    if (!alive(e.key)) continue;
    const BvhNode& a = nodes_P[e.ip];
    const BvhNode& b = nodes_S[e.is];
    if (a.is_leaf() && b.is_leaf()) {
      bool go_on;
      if constexpr (std::is_invocable_v<LeafFn&, int, int, double>)
        go_on = on_leaf_pair(e.ip, e.is, e.key);
      else
        go_on = on_leaf_pair(e.ip, e.is);
      if (!go_on) break;
      continue;
    }
    const bool split_P = b.is_leaf() || (!a.is_leaf() && NodeSize2(a) >= NodeSize2(b));
    DescentEntry child[2];
    int n = 0;
    for (int c = 0; c < 2; ++c) {
      const int32_t ip = split_P ? (c == 0 ? e.ip + 1 : a.right_or_first) : e.ip;
      const int32_t is = split_P ? e.is : (c == 0 ? e.is + 1 : b.right_or_first);
      ++tests;
      if (test(nodes_P[ip], nodes_S[is], &key)) child[n++] = {ip, is, key};
    }
    // Lower key on top of the stack: visited first.
    if (n == 2 && child[0].key < child[1].key) std::swap(child[0], child[1]);
    for (int c = 0; c < n; ++c) stack[top++] = child[c];
  }
  if (counters) counters->box_tests += tests;
}

}  // namespace internal

inline constexpr int kDescentStackCapacity = 192;

template <typename NodeTest, typename Alive, typename LeafFn>
void DescendBvhPair(const Bvh& bvh_P, const Bvh& bvh_S, NodeTest&& test, Alive&& alive,
                    LeafFn&& on_leaf_pair, ProximityCounters* counters = nullptr) {
  if (bvh_P.empty() || bvh_S.empty()) return;
  const int needed = bvh_P.depth() + bvh_S.depth() + 1;
  if (needed <= kDescentStackCapacity) {
    std::array<internal::DescentEntry, kDescentStackCapacity> stack;
    internal::DescendWithStack(stack, bvh_P, bvh_S, test, alive, on_leaf_pair, counters);
  } else {
    std::vector<internal::DescentEntry> stack(needed);
    internal::DescendWithStack(stack, bvh_P, bvh_S, test, alive, on_leaf_pair, counters);
  }
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
