#pragma once
// The one descent of a single BVH that the point and ray queries use (ray
// crossings for containment, point clearance). It is parameterised by
//   test(node) -> bool           descend into this node?
//   on_slots(first, end) -> bool the triangles in bvh.order() slots
//                                [first, end) of a kept leaf (or of a whole
//                                subtree, see below); false stops the descent.
// Children are visited left first. The descent keeps at most
// `stack_capacity` pending nodes (clamped to [0, kBvhStackCapacity]); a
// subtree that would need more is handed to on_slots whole (its triangles
// are contiguous in bvh.order()), so a BVH of any depth, balanced or not, is
// traversed correctly with a fixed, checked stack. Returns false if on_slots
// stopped it. (Pair queries descend two BVHs at once: bvh_pair_descent.h.)
#include <algorithm>
#include <array>
#include <cstdint>

#include "pd_core/proximity/bvh.h"

namespace pd {

// Most pending nodes DescendBvh keeps (a balanced BVH of n triangles needs
// about log2(n) of them).
inline constexpr int kBvhStackCapacity = 64;

// Leaf slots [first, end) in bvh.order() of the subtree rooted at `node`:
// its leftmost leaf's first slot to its rightmost leaf's end (the build lays
// every subtree's triangles out contiguously).
inline void SubtreeSlots(const Bvh& bvh, int node, int* first, int* end) {
  const auto& nodes = bvh.nodes();
  int left = node, right = node;
  while (!nodes[left].is_leaf()) ++left;
  while (!nodes[right].is_leaf()) right = nodes[right].right_or_first;
  *first = nodes[left].right_or_first;
  *end = nodes[right].right_or_first + nodes[right].count;
}

template <typename NodeTest, typename SlotsFn>
bool DescendBvh(const Bvh& bvh, NodeTest&& test, SlotsFn&& on_slots,
                int stack_capacity = kBvhStackCapacity, int64_t* node_tests = nullptr) {
  if (bvh.empty()) return true;
  const int capacity = std::clamp(stack_capacity, 0, kBvhStackCapacity);
  std::array<int32_t, kBvhStackCapacity> stack;
  int top = 0;
  int node = 0;
  int64_t tests = 0;
  bool completed = true;
  for (;;) {
    const BvhNode& n = bvh.nodes()[node];
    ++tests;
    if (test(n)) {
      if (!n.is_leaf() && top < capacity) {
        stack[top++] = n.right_or_first;  // visit the left child next
        ++node;
        continue;
      }
      int first = n.right_or_first, end = n.right_or_first + n.count;
      if (!n.is_leaf()) SubtreeSlots(bvh, node, &first, &end);  // stack full
      if (!on_slots(first, end)) {
        completed = false;
        break;
      }
    }
    if (top == 0) break;
    node = stack[--top];
  }
  if (node_tests) *node_tests += tests;
  return completed;
}

}  // namespace pd
