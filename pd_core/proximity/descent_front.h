#pragma once
// The cut where a best-first BVH pair descent ended (Ehmann and Lin's
// front), kept so the next descent of the same pair of hierarchies can
// start there instead of at the roots. A cut holds every node pair the
// descent rejected, every leaf pair it reached and every pair it left
// pending, so each leaf pair of the full pair tree has exactly one
// ancestor-or-self in it: a descent from the cut reaches every leaf pair a
// descent from the roots does (and, at most, a few whose ancestors above
// the cut the node test would have rejected). A cut is pose-independent; it
// pays where consecutive descents look at nearly the same place: the CCDs
// of one PolyDepth search, 20-500 um apart, which descend the same ~1-2k
// pairs near the contact each time. Starting there skips the internal
// pairs above the cut (about half a descent's box tests).
#include <cstddef>
#include <limits>
#include <vector>

#include "pd_core/geometry/pose.h"
#include "pd_core/proximity/bvh_pair_descent.h"

namespace pd {

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
  template <typename NodeTest, typename Alive, typename LeafFn, typename Stop>
  friend bool DescendBvhPairFromFront(const Bvh&, const Bvh&, NodeTest&&, Alive&&, LeafFn&&,
                                      ProximityCounters*, DescentFront*, size_t, Stop&&,
                                      double*);
  std::vector<NodePair> cut_, next_;
  std::vector<internal::DescentEntry> kept_;  // scratch: the cut's pairs the test keeps
};

// A best-first DescendBvhPair (same test, alive, leaf action, stop and
// stopped_at) from the cut `front` holds, or from the roots when it holds
// none or more than max_cut pairs (a cut only grows: one that has followed
// a contact far would cost more than the roots). Replaces the cut with this
// descent's. Box tests count every pair tested, the cut's included.
template <typename NodeTest, typename Alive, typename LeafFn, typename Stop>
bool DescendBvhPairFromFront(const Bvh& bvh_P, const Bvh& bvh_S, NodeTest&& test, Alive&& alive,
                             LeafFn&& on_leaf_pair, ProximityCounters* counters,
                             DescentFront* front, size_t max_cut, Stop&& stop,
                             double* stopped_at) {
  if (front->cut_.empty() || front->cut_.size() > max_cut) {
    front->next_.clear();
    const bool completed =
        DescendBvhPair<DescentOrder::kBestFirst>(bvh_P, bvh_S, test, alive, on_leaf_pair,
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
  front->kept_.clear();
  for (const NodePair& p : front->cut_) {
    ++d.tests;
    internal::DescentEntry e{p.ip, p.is, -std::numeric_limits<double>::infinity()};
    if (test(d.nodes_P[p.ip], d.nodes_S[p.is], &e.key))
      front->kept_.push_back(e);
    else
      d.Cut(e);
  }
  bool completed = true;
  auto run = [&](auto& stack) {
    std::array<internal::DescentEntry, kBestFirstHeapCapacity> heap;
    double unused = 0.0;
    completed = d.BestFirst(heap, stack, front->kept_.data(), front->kept_.size(), stop,
                            stopped_at ? stopped_at : &unused);
  };
  const int needed = bvh_P.depth() + bvh_S.depth() + 1;
  if (needed <= kDescentStackCapacity) {
    std::array<internal::DescentEntry, kDescentStackCapacity> stack;
    run(stack);
  } else {
    std::vector<internal::DescentEntry> stack(needed);
    run(stack);
  }
  std::swap(front->cut_, front->next_);
  if (counters) counters->box_tests += d.tests;
  return completed;
}

}  // namespace pd
