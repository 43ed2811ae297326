#pragma once
// Hand-made BVHs for descent tests: axis-aligned unit boxes along x in a
// degenerate chain or a complete binary tree, and their overlap test.
#include <utility>
#include <vector>

#include "pd_core/proximity/bvh.h"

namespace pd::test {

// A degenerate "caterpillar" tree over n unit-spaced leaves along x: node
// 2k is internal with a leaf (2k+1) on the left and the rest of the chain on
// the right, so the depth is about n. Axis-aligned boxes.
inline Bvh Caterpillar(int n, double x0) {
  std::vector<BvhNode> nodes;
  std::vector<int32_t> order;
  for (int k = 0; k < n; ++k) order.push_back(k);
  for (int k = 0; k < n; ++k) {
    const bool last = k == n - 1;
    if (!last) {
      BvhNode internal;
      internal.R_MB = Matrix3::Identity();
      // Spans leaves k .. n-1: x in [x0 + k - 0.4, x0 + n - 1 + 0.4].
      const double lo = x0 + k - 0.4, hi = x0 + n - 1 + 0.4;
      internal.center_M = Vector3(0.5 * (lo + hi), 0, 0);
      internal.half_B = Vector3(0.5 * (hi - lo), 0.4, 0.4);
      internal.count = 0;
      nodes.push_back(internal);
    }
    BvhNode leaf;
    leaf.R_MB = Matrix3::Identity();
    leaf.center_M = Vector3(x0 + k, 0, 0);
    leaf.half_B = Vector3(0.4, 0.4, 0.4);
    leaf.right_or_first = k;
    leaf.count = 1;
    nodes.push_back(leaf);
    if (!last) nodes[nodes.size() - 2].right_or_first = static_cast<int32_t>(nodes.size());
  }
  return Bvh::FromNodes(std::move(nodes), std::move(order));
}

inline bool Overlap(const BvhNode& a, const BvhNode& b) {
  return ((a.center_M - b.center_M).cwiseAbs() - a.half_B - b.half_B).maxCoeff() <= 0.0;
}

// A complete binary tree over 2^levels unit leaves spaced `spacing` apart
// along x (spacing 0: all in one place). Axis-aligned boxes.
inline Bvh Balanced(int levels, double spacing) {
  std::vector<BvhNode> nodes;
  std::vector<int32_t> order;
  auto build = [&](auto& self, int first, int count) -> void {
    const int index = static_cast<int>(nodes.size());
    nodes.emplace_back();
    BvhNode& n = nodes.back();
    n.R_MB = Matrix3::Identity();
    const double lo = first * spacing - 0.4, hi = (first + count - 1) * spacing + 0.4;
    n.center_M = Vector3(0.5 * (lo + hi), 0, 0);
    n.half_B = Vector3(0.5 * (hi - lo), 0.4, 0.4);
    if (count == 1) {
      n.right_or_first = static_cast<int32_t>(order.size());
      n.count = 1;
      order.push_back(first);
      return;
    }
    self(self, first, count / 2);
    nodes[index].right_or_first = static_cast<int32_t>(nodes.size());
    self(self, first + count / 2, count - count / 2);
  };
  build(build, 0, 1 << levels);
  return Bvh::FromNodes(std::move(nodes), std::move(order));
}

}  // namespace pd::test
