#pragma once
// The cut where a BVH pair descent ended (Ehmann and Lin's front), kept so
// the next descent of the same pair of hierarchies can start there instead of
// at the roots. A cut holds every node pair the descent rejected, every leaf
// pair it reached and every pair it left pending, so each leaf pair of the
// full pair tree has exactly one ancestor-or-self in it: a descent from the
// cut reaches every leaf pair a descent from the roots does (and, at most, a
// few whose ancestors above the cut the node test would have rejected). A
// cut is pose- and test-independent; it pays where consecutive descents look
// at nearly the same place: the CCDs, localisations and collision tests of
// one PolyDepth search, 20-500 um apart, which descend the same ~1-2k pairs
// near the contact each time. Starting there skips the internal pairs above
// the cut (about half a descent's box tests).
#include <cstddef>
#include <limits>
#include <vector>

#include "pd_core/geometry/pose.h"
#include "pd_core/proximity/bvh_pair_descent.h"
#include "pd_core/proximity/model_pair.h"

namespace pd {

class DescentFront;
template <DescentOrder kOrder, typename NodeTest, typename Alive, typename LeafFn,
          typename Stop = internal::NeverStop>
bool DescendBvhPairFromFront(const Bvh& bvh_P, const Bvh& bvh_S, NodeTest&& test, Alive&& alive,
                             LeafFn&& on_leaf_pair, ProximityCounters* counters,
                             DescentFront* front, size_t max_cut, Stop&& stop = Stop{},
                             double* stopped_at = nullptr);

class DescentFront {
 public:
  DescentFront() {
    cut_.reserve(4096);
    next_.reserve(4096);
    kept_.reserve(4096);
  }
  void Invalidate() { cut_.clear(); }
  // Where the descent that made the cut ended (the caller's configuration,
  // e.g. a CCD's landing point in S, m): a descent near there reuses it.
  Vector3 q_S = Vector3::Zero();
  // Pairs in the cut (0: none kept; a descent starts at the roots).
  size_t size() const { return cut_.size(); }
  const std::vector<NodePair>& pairs() const { return cut_; }

 private:
  template <DescentOrder kOrder, typename NodeTest, typename Alive, typename LeafFn,
            typename Stop>
  friend bool DescendBvhPairFromFront(const Bvh&, const Bvh&, NodeTest&&, Alive&&, LeafFn&&,
                                      ProximityCounters*, DescentFront*, size_t, Stop&&,
                                      double*);
  std::vector<NodePair> cut_, next_;
  std::vector<internal::DescentEntry> kept_;  // scratch: the cut's pairs the test keeps
};

// A descent starts at the last one's cut when it looks within this fraction
// of the pair's size of where the last ended (a search's next CCD from the
// last landing, the localisation and collision tests there). haptic_work
// total work: 1e-4 -1.3%, 1e-3 -2.4%, 3e-3 -3.2%, 1e-2 -3.3% (max work up on
// two paths), unlimited -0.1% (max work fandisk 13.1k -> 15.9k, knot1_bunny
// 19.2k -> 22.2k): descents from elsewhere (a cross-check probe, a cold
// query's next start) find the cut refined around another contact; for the
// CCD alone, unlimited, cold random queries (bench_pd, 48 cases) did 41-81%
// more box and triangle tests. A cut only grows (no merging back: the
// hierarchies keep no parent links), so past kMaxFrontPairs the descent
// starts at the roots. Kept across queries the cuts grew fine: haptic_work
// total work +19% (+5% capped at 1500); the solver empties it at each query.
inline constexpr double kFrontReuseDistance = 3e-3;
inline constexpr size_t kMaxFrontPairs = 4096;
// A best-first descent from a cut asks the caller's stop once per this many
// of the cut's pairs while it tests them (and before each pop after).
inline constexpr size_t kCutPairsPerStopAsk = 64;

// The pair's front for a descent at q_S (m, in S): null when the pair keeps
// none; emptied first (the descent starts at the roots and leaves a new cut)
// when the last descent ended farther than kFrontReuseDistance from q_S.
// The caller sets q_S once it knows where its descent ended.
inline DescentFront* FrontNear(const ModelPair& pair, const Vector3& q_S) {
  DescentFront* front = pair.front;
  if (front != nullptr && (q_S - front->q_S).norm() > kFrontReuseDistance * pair.size())
    front->Invalidate();
  return front;
}

// DescendBvhPair (same order, test, alive, leaf action, and for best-first
// stop and stopped_at) from the cut `front` holds, or from the roots when it
// holds none or more than max_cut pairs (a cut only grows: one that has
// followed a contact far would cost more than the roots). Replaces the cut
// with this descent's. Box tests count every pair tested, the cut's
// included.
template <DescentOrder kOrder, typename NodeTest, typename Alive, typename LeafFn, typename Stop>
bool DescendBvhPairFromFront(const Bvh& bvh_P, const Bvh& bvh_S, NodeTest&& test, Alive&& alive,
                             LeafFn&& on_leaf_pair, ProximityCounters* counters,
                             DescentFront* front, size_t max_cut, Stop&& stop,
                             double* stopped_at) {
  if (front->cut_.empty() || front->cut_.size() > max_cut) {
    front->next_.clear();
    const bool completed = DescendBvhPair<kOrder>(bvh_P, bvh_S, test, alive, on_leaf_pair,
                                                  counters, 0, 0, stop, stopped_at, &front->next_);
    std::swap(front->cut_, front->next_);
    return completed;
  }
  if (bvh_P.empty() || bvh_S.empty()) return true;
  internal::Descent<std::remove_reference_t<NodeTest>, std::remove_reference_t<Alive>,
                    std::remove_reference_t<LeafFn>>
      d{bvh_P.nodes(), bvh_S.nodes(), test, alive, on_leaf_pair};
  front->next_.clear();
  d.cut = &front->next_;
  const std::vector<NodePair>& cut = front->cut_;
  // The cut's pair r, tested: kept (into *e) or cut again.
  auto test_pair = [&](size_t r, internal::DescentEntry* e) {
    ++d.tests;
    *e = {cut[r].ip, cut[r].is, -std::numeric_limits<double>::infinity()};
    if (test(d.nodes_P[e->ip], d.nodes_S[e->is], &e->key)) return true;
    d.Cut(*e);
    return false;
  };
  bool completed = true;
  auto counted_stop = internal::CountedStop(d, counters, stop);
  auto run = [&](auto& stack) {
    internal::DescentEntry e;
    if constexpr (kOrder == DescentOrder::kBestFirst) {
      // The caller's stop first, as a descent from the roots asks it after
      // one test: with no pair tested, nothing is known beyond -inf, and
      // the cut stays as it is.
      if (counted_stop()) {
        if (stopped_at) *stopped_at = -std::numeric_limits<double>::infinity();
        front->next_.assign(cut.begin(), cut.end());
        return;
      }
      // Every pair of the cut tested first: the heap orders them all. The
      // stop is asked along the way too (a cut holds up to max_cut pairs);
      // stopped there, nothing is known beyond -inf and the cut stays.
      auto& kept = front->kept_;
      kept.clear();
      for (size_t r = 0; r < cut.size(); ++r) {
        if (r % kCutPairsPerStopAsk == kCutPairsPerStopAsk - 1 && counted_stop()) {
          if (stopped_at) *stopped_at = -std::numeric_limits<double>::infinity();
          front->next_.assign(cut.begin(), cut.end());
          return;
        }
        if (test_pair(r, &e)) kept.push_back(e);
      }
      std::array<internal::DescentEntry, kBestFirstHeapCapacity> heap;
      double unused = 0.0;
      completed = d.BestFirst(heap, stack, kept.data(), kept.size(), counted_stop,
                              stopped_at ? stopped_at : &unused);
    } else {
      // Each pair descended as soon as it is kept: a descent the leaf
      // action stops early (a collision test's first hit) tests no more of
      // the cut than it needs; the rest is cut again as it stands.
      for (size_t r = 0; r < cut.size(); ++r) {
        if (!test_pair(r, &e) || d.DepthFirst(stack, e)) continue;
        d.CutAll(cut.data() + r + 1, cut.size() - r - 1);
        completed = false;
        break;
      }
    }
  };
  internal::WithDescentStack(bvh_P, bvh_S, run);
  std::swap(front->cut_, front->next_);
  if (counters) counters->box_tests += d.tests;
  return completed;
}

}  // namespace pd
