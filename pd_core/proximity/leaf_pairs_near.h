#pragma once
// The leaf pairs a query at a configuration (or along a segment of them)
// must look at: from the pair's candidate list when that covers the
// configurations (only its near prefix, see candidate_pairs.h), or from the
// pair's record (the last CCD's or localisation's) when that answers for
// them (see leaf_pair_record.h), whichever holds fewer; otherwise from a
// BVH descent (from the last descent's cut when that ended near here, see
// descent_front.h).
// All paths apply the same node test, so the caller sees the same pairs
// either way, minus those the list proves too far and plus, from a record, a
// few whose ancestors the descent would have rejected (their features are
// farther than `distance`).
#include <algorithm>
#include <type_traits>

#include "pd_core/proximity/bvh_pair_descent.h"
#include "pd_core/proximity/candidate_pairs.h"
#include "pd_core/proximity/descent_front.h"
#include "pd_core/proximity/leaf_pair_record.h"
#include "pd_core/proximity/model_pair.h"

namespace pd {

// Calls on_leaf_pair(ip, is) for every leaf pair that passes
// may_touch(a, b) among those that can come within `distance` (m) of each
// other with the probe translated by a point of [q_a_S, q_b_S].
template <typename NodeTest, typename LeafFn>
void ForEachLeafPairNear(const ModelPair& pair, const Vector3& q_a_S, const Vector3& q_b_S,
                         double distance, NodeTest&& may_touch, LeafFn&& on_leaf_pair) {
  // The node test with a key (a descent order) or without.
  auto node_test = [&](const BvhNode& a, const BvhNode& b, double* key) {
    if constexpr (std::is_invocable_v<NodeTest&, const BvhNode&, const BvhNode&, double*>)
      return may_touch(a, b, key);
    else
      return may_touch(a, b);
  };
  const LeafPairRecord* record = pair.recorded;
  const bool record_covers = record != nullptr && record->Covers(q_a_S, q_b_S, distance);
  const CandidatePairs* list = pair.candidates;
  if (list != nullptr) {
    double unused_key;
    const double displacement =
        std::max(list->Displacement(pair, q_a_S), list->Displacement(pair, q_b_S));
    const int n =
        displacement + distance < list->radius() ? list->NearCount(distance, displacement) : -1;
    // A record that answers here and holds fewer pairs than the list's
    // prefix is walked instead: a dense list the probe has moved across
    // walks most of its entries for every check just off an answer
    // (fandisk_elephant: three collision tests 0.2 um apart, 1.2k tests
    // each; haptic_work total work -0.5%, fandisk -1.4%, same answers).
    if (n >= 0 && !(record_covers && record->pairs.size() < static_cast<size_t>(n))) {
      const auto& entries = list->entries();
      const auto& nodes_P = pair.P.bvh().nodes();
      const auto& nodes_S = pair.S.bvh().nodes();
      // Along each entry's separating axis first (a dot product): only the
      // pairs the motion may have brought within `distance` get a box test.
      Vector3 shift_a, shift_b;
      double rot = 0.0;
      list->MotionSinceBuild(pair, q_a_S, &shift_a, &rot);
      list->MotionSinceBuild(pair, q_b_S, &shift_b, &rot);  // one pose: the same rot
      int64_t tested = 0;
      for (int k = 0; k < n; ++k) {
        const CandidatePairs::Entry& e = entries[k];
        if (e.StaysApart(shift_a, shift_b, rot, distance)) continue;
        if (nodes_P[e.ip].is_leaf() && nodes_S[e.is].is_leaf()) {
          ++tested;
          if (!node_test(nodes_P[e.ip], nodes_S[e.is], &unused_key)) continue;
          if (!on_leaf_pair(e.ip, e.is)) break;
        } else if (!DescendBvhPair(pair.P.bvh(), pair.S.bvh(), node_test,
                                   [](double) { return true; }, on_leaf_pair, pair.counters,
                                   e.ip, e.is)) {
          break;
        }
      }
      if (pair.counters) pair.counters->box_tests += tested;
      return;
    }
  }
  if (record_covers) {
    // The recorded leaf pairs near these configurations: the same node
    // test on each (the pairs a descent would find are among them).
    double unused_key;
    const auto& nodes_P = pair.P.bvh().nodes();
    const auto& nodes_S = pair.S.bvh().nodes();
    int64_t tested = 0;
    for (const LeafPairRecord::LeafPair& e : record->pairs) {
      ++tested;
      if (!node_test(nodes_P[e.ip], nodes_S[e.is], &unused_key)) continue;
      if (!on_leaf_pair(e.ip, e.is)) break;
    }
    if (pair.counters) pair.counters->box_tests += tested;
    return;
  }
  // From the last descent's cut where it ended near here (descent_front.h).
  if (DescentFront* front = FrontNear(pair, q_a_S)) {
    DescendBvhPairFromFront<DescentOrder::kDepthFirst>(pair.P.bvh(), pair.S.bvh(), node_test,
                                                       [](double) { return true; }, on_leaf_pair,
                                                       pair.counters, front, kMaxFrontPairs);
    front->q_S = q_b_S;
    return;
  }
  DescendBvhPair(pair.P.bvh(), pair.S.bvh(), node_test, [](double) { return true; }, on_leaf_pair,
                 pair.counters);
}

}  // namespace pd
