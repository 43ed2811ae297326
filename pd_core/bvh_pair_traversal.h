#pragma once
// Simultaneous descent of a probe BVH and a scene BVH. `may_touch(a, b)`
// prunes a node pair; `on_leaf_pair(tp, ts)` sees every surviving triangle
// pair and returns false to stop early. Stack-allocated: no heap use.
#include <array>
#include <utility>

#include "pd_core/box_overlap.h"
#include "pd_core/candidate_pairs.h"
#include "pd_core/model_pair.h"

namespace pd {

template <typename NodeTest, typename LeafFn>
void TraverseBvhPairs(const Bvh& bvh_P, const Bvh& bvh_S, NodeTest&& may_touch,
                      LeafFn&& on_leaf_pair) {
  if (bvh_P.empty() || bvh_S.empty()) return;
  const auto& nodes_P = bvh_P.nodes();
  const auto& nodes_S = bvh_S.nodes();
  // Each step pops one pair and pushes at most two, descending one side, so
  // the stack never exceeds depth_P + depth_S + 1 entries.
  std::array<std::pair<int, int>, 256> stack;
  int top = 0;
  stack[top++] = {0, 0};
  while (top > 0) {
    const auto [ip, is] = stack[--top];
    const BvhNode& a = nodes_P[ip];
    const BvhNode& b = nodes_S[is];
    if (!may_touch(a, b)) continue;
    if (a.is_leaf() && b.is_leaf()) {
      for (int i = 0; i < a.count; ++i) {
        for (int j = 0; j < b.count; ++j) {
          if (!on_leaf_pair(bvh_P.order()[a.right_or_first + i],
                            bvh_S.order()[b.right_or_first + j]))
            return;
        }
      }
      continue;
    }
    const bool split_P =
        b.is_leaf() || (!a.is_leaf() && NodeSize2(a) >= NodeSize2(b));
    if (split_P) {
      stack[top++] = {a.right_or_first, is};
      stack[top++] = {ip + 1, is};
    } else {
      stack[top++] = {ip, b.right_or_first};
      stack[top++] = {ip, is + 1};
    }
  }
}

// Like TraverseBvhPairs, but walks the pair's candidate list instead when
// `use_list` (the caller checked that the list covers its configurations);
// `may_touch` then filters the listed leaf pairs.
template <typename NodeTest, typename LeafFn>
void ForEachLeafPair(const ModelPair& pair, bool use_list, NodeTest&& may_touch,
                     LeafFn&& on_leaf_pair) {
  if (!use_list) {
    TraverseBvhPairs(pair.P.bvh(), pair.S.bvh(), may_touch, on_leaf_pair);
    return;
  }
  const Bvh& bvh_P = pair.P.bvh();
  const Bvh& bvh_S = pair.S.bvh();
  for (const auto& [ip, is] : pair.candidates->leaf_pairs()) {
    const BvhNode& a = bvh_P.nodes()[ip];
    const BvhNode& b = bvh_S.nodes()[is];
    if (!may_touch(a, b)) continue;
    for (int i = 0; i < a.count; ++i)
      for (int j = 0; j < b.count; ++j)
        if (!on_leaf_pair(bvh_P.order()[a.right_or_first + i], bvh_S.order()[b.right_or_first + j]))
          return;
  }
}

}  // namespace pd
