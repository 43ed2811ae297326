// A descent's cut (pd_core/proximity/descent_front.h): whatever ends the
// descent (completion, a pair not alive, the caller's stop, the leaf action),
// the cut holds each leaf pair of the full pair tree under exactly one of
// its pairs; a descent from a cut reaches the leaf pairs a descent from the
// roots reaches, with fewer box tests when it looks near where the cut was
// made, and leaves a cut of its own. Localisations and collision tests near
// the last descent's end start there and answer as from the roots.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "pd_core/geometry/make_shapes.h"
#include "pd_core/mesh/collision_model.h"
#include "pd_core/polydepth/contact_constraints.h"
#include "pd_core/proximity/bvh_pair_descent.h"
#include "pd_core/proximity/descent_front.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"
#include "tests/pd_core/synthetic_bvh.h"

namespace pd {
namespace {

using test::Balanced;

// End (one past the last node) of each node's subtree in the depth-first
// layout (left child = index + 1, right child = right_or_first).
std::vector<int> SubtreeEnds(const Bvh& bvh) {
  const auto& nodes = bvh.nodes();
  std::vector<int> end(nodes.size());
  auto visit = [&](auto& self, int i) -> int {
    if (nodes[i].is_leaf()) return end[i] = i + 1;
    self(self, i + 1);
    return end[i] = self(self, nodes[i].right_or_first);
  };
  visit(visit, 0);
  return end;
}

std::vector<int> Leaves(const Bvh& bvh) {
  std::vector<int> leaves;
  for (int i = 0; i < static_cast<int>(bvh.nodes().size()); ++i)
    if (bvh.nodes()[i].is_leaf()) leaves.push_back(i);
  return leaves;
}

// For every leaf pair of a x b: how many pairs of `cut` hold it (node pair
// (ip, is) holds leaf pair (lp, ls) when lp is in ip's subtree and ls in
// is's). A complete cut holds each exactly once.
std::vector<int> Holders(const Bvh& a, const Bvh& b, const std::vector<NodePair>& cut) {
  const std::vector<int> end_a = SubtreeEnds(a), end_b = SubtreeEnds(b);
  std::vector<int> holders;
  for (int lp : Leaves(a))
    for (int ls : Leaves(b)) {
      int n = 0;
      for (const NodePair& c : cut)
        n += c.ip <= lp && lp < end_a[c.ip] && c.is <= ls && ls < end_b[c.is];
      holders.push_back(n);
    }
  return holders;
}

// Box overlap with the probe tree shifted by `shift` along x, keyed by the
// pair's distance from x = 20 (no lower than the parent's).
auto ShiftedOverlap(double shift) {
  return [shift](const BvhNode& x, const BvhNode& y, double* key) {
    BvhNode moved = x;
    moved.center_M.x() += shift;
    *key = std::max(*key, std::abs(moved.center_M.x() - 20.0) - moved.half_B.x());
    return test::Overlap(moved, y);
  };
}

template <DescentOrder kOrder = DescentOrder::kBestFirst>
std::set<std::pair<int, int>> Descend(const Bvh& a, const Bvh& b, double shift,
                                      DescentFront* front, ProximityCounters* counters) {
  std::set<std::pair<int, int>> reached;
  auto leaf = [&](int ip, int is) {
    reached.insert({ip, is});
    return true;
  };
  if (front != nullptr) {
    DescendBvhPairFromFront<kOrder>(a, b, ShiftedOverlap(shift), [](double) { return true; },
                                    leaf, counters, front, 1u << 20);
  } else {
    DescendBvhPair<kOrder>(a, b, ShiftedOverlap(shift), [](double) { return true; }, leaf,
                           counters);
  }
  return reached;
}

TEST(DescentFront, ACutHoldsEachLeafPairOnceHoweverTheDescentEnds) {
  const Bvh a = Balanced(5, 1.0), b = Balanced(5, 1.0);
  const size_t leaf_pairs = Leaves(a).size() * Leaves(b).size();
  ASSERT_EQ(leaf_pairs, 1024u);
  auto always = [](double) { return true; };
  struct Ending {
    const char* name;
    double alive_below;  // keys at or above: not alive
    int stop_after;      // pops before the caller's stop (-1: never)
    int leaves_before_stop;  // leaf pairs before the leaf action stops it (-1: never)
  };
  for (const Ending& e : {Ending{"complete", 1e300, -1, -1}, Ending{"not alive", 3.0, -1, -1},
                          Ending{"stopped", 1e300, 25, -1}, Ending{"leaf stop", 1e300, -1, 10}}) {
    DescentFront front;
    int pops = 0, leaves = 0;
    auto stop = [&] { return e.stop_after >= 0 && ++pops > e.stop_after; };
    auto leaf = [&](int, int) { return e.leaves_before_stop < 0 || ++leaves < e.leaves_before_stop; };
    DescendBvhPairFromFront<DescentOrder::kBestFirst>(a, b, ShiftedOverlap(0.3),
                            [&](double key) { return key < e.alive_below; }, leaf, nullptr,
                            &front, 1u << 20, stop, nullptr);
    ASSERT_GT(front.size(), 0u) << e.name;
    EXPECT_LT(front.size(), leaf_pairs) << e.name << ": the cut is coarser than the leaves";
    const std::vector<int> holders = Holders(a, b, front.pairs());
    EXPECT_EQ(std::count(holders.begin(), holders.end(), 1), static_cast<long>(leaf_pairs))
        << e.name;
    // A descent from that cut leaves a complete cut too.
    DescendBvhPairFromFront<DescentOrder::kBestFirst>(a, b, ShiftedOverlap(1.7), always,
                                                      [](int, int) { return true; }, nullptr,
                                                      &front, 1u << 20);
    const std::vector<int> again = Holders(a, b, front.pairs());
    EXPECT_EQ(std::count(again.begin(), again.end(), 1), static_cast<long>(leaf_pairs))
        << e.name << ", then from its cut";
  }
}

template <DescentOrder kOrder>
void ExpectFromACutItReachesWhatADescentFromTheRootsReaches() {
  const Bvh a = Balanced(6, 1.0), b = Balanced(6, 1.0);
  for (double next : {0.35, 0.5, 3.2, -20.0}) {
    DescentFront front;
    ProximityCounters first;
    const auto made_at = Descend<kOrder>(a, b, 0.3, &front, &first);  // empty: from the roots
    EXPECT_EQ(made_at, Descend<kOrder>(a, b, 0.3, nullptr, nullptr));
    ProximityCounters from_cut, from_roots;
    const auto reached = Descend<kOrder>(a, b, next, &front, &from_cut);
    EXPECT_EQ(reached, Descend<kOrder>(a, b, next, nullptr, &from_roots)) << "shift " << next;
    // The cut it leaves is complete.
    const std::vector<int> holders = Holders(a, b, front.pairs());
    EXPECT_EQ(std::count(holders.begin(), holders.end(), 1),
              static_cast<long>(holders.size()));
    // Near where the cut was made, the pairs above it are not tested again.
    if (std::abs(next - 0.3) < 0.3) {
      EXPECT_FALSE(reached.empty());
      EXPECT_LT(from_cut.box_tests, from_roots.box_tests * 2 / 3) << "shift " << next;
    }
  }
}

TEST(DescentFront, FromACutItReachesWhatADescentFromTheRootsReaches) {
  ExpectFromACutItReachesWhatADescentFromTheRootsReaches<DescentOrder::kBestFirst>();
  ExpectFromACutItReachesWhatADescentFromTheRootsReaches<DescentOrder::kDepthFirst>();
}

// A caller out of budget before the descent starts (a bounded CCD): no pair
// of the cut is tested, nothing is known contact-free (-inf), the cut stays.
TEST(DescentFront, StoppedAtOnceItTestsNothingAndKeepsTheCut) {
  const Bvh a = Balanced(6, 1.0), b = Balanced(6, 1.0);
  DescentFront front;
  Descend(a, b, 0.3, &front, nullptr);
  const std::vector<NodePair> before = front.pairs();
  ASSERT_GT(before.size(), 10u);
  ProximityCounters counters;
  double stopped_at = 7.0;
  int leaves = 0;
  DescendBvhPairFromFront<DescentOrder::kBestFirst>(
      a, b, ShiftedOverlap(0.35), [](double) { return true; },
      [&](int, int) { return ++leaves > 0; }, &counters, &front, 1u << 20, [] { return true; },
      &stopped_at);
  EXPECT_EQ(counters.box_tests, 0);
  EXPECT_EQ(leaves, 0);
  EXPECT_EQ(stopped_at, -std::numeric_limits<double>::infinity());
  ASSERT_EQ(front.size(), before.size());
  for (size_t i = 0; i < before.size(); ++i) {
    EXPECT_EQ(front.pairs()[i].ip, before[i].ip);
    EXPECT_EQ(front.pairs()[i].is, before[i].is);
  }
}

TEST(DescentFront, ACutLargerThanTheCapStartsAtTheRoots) {
  const Bvh a = Balanced(6, 1.0), b = Balanced(6, 1.0);
  DescentFront front;
  Descend(a, b, 0.3, &front, nullptr);
  const size_t made = front.size();
  ASSERT_GT(made, 10u);
  ProximityCounters capped, roots;
  std::set<std::pair<int, int>> reached;
  DescendBvhPairFromFront<DescentOrder::kBestFirst>(a, b, ShiftedOverlap(0.4), [](double) { return true; },
                          [&](int ip, int is) {
                            reached.insert({ip, is});
                            return true;
                          },
                          &capped, &front, made - 1);
  EXPECT_EQ(reached, Descend(a, b, 0.4, nullptr, &roots));
  EXPECT_EQ(capped.box_tests, roots.box_tests);  // the same descent, from the roots
}

// PolyDepth's steps near a contact: localisations and collision tests at
// configurations a few thousandths of the pair's size apart, on meshes.
TEST(DescentFront, LocalisationsAndCollisionTestsNearTheLastStartAtItsCut) {
  auto P = CollisionModel::Build(MakeIcosphere(0.3, 4));
  auto S = CollisionModel::Build(MakeTorusKnot(2, 3, 0.2, 1.0, 256, 16));
  const Isometry3 X_WS = Isometry3::Identity();
  Isometry3 X_WP = Isometry3::Identity();
  X_WP.translation() = S->mesh().vertices[0] + Vector3(0.05, 0.0, 0.0);
  ModelPair with(*P, *S, X_WP, X_WS);
  const ModelPair without(*P, *S, X_WP, X_WS);
  DescentFront front;
  ProximityCounters cut_counters, root_counters;
  with.front = &front;
  with.counters = &cut_counters;
  ModelPair counted = without;
  counted.counters = &root_counters;
  using Key = std::tuple<int, int, int>;
  auto keys = [](const std::vector<ContactConstraint>& cs) {
    std::set<Key> k;
    for (const ContactConstraint& c : cs)
      k.insert({static_cast<int>(c.kind), c.feature_P, c.feature_S});
    return k;
  };
  const double step = 1e-3 * with.size();  // within kFrontReuseDistance
  const double distance = 1e-3 * with.size();  // 10x PolyDepth's contact distance
  int colliding = 0, constraints = 0;
  for (int k = 0; k < 12; ++k) {
    const Vector3 q = k * step * Vector3(0.6, 0.8, 0.0);
    std::vector<ContactConstraint> a, b;
    CollectContactConstraints(with, q, distance, &a);
    CollectContactConstraints(counted, q, distance, &b);
    EXPECT_EQ(keys(a), keys(b)) << "step " << k;
    constraints += static_cast<int>(a.size());
    const bool hit = InCollision(with, q);
    EXPECT_EQ(hit, InCollision(counted, q)) << "step " << k;
    colliding += hit;
    if (k == 0) {  // the first starts at the roots: no cut yet
      cut_counters = ProximityCounters{};
      root_counters = ProximityCounters{};
    }
  }
  EXPECT_GT(constraints, 100);
  EXPECT_GT(colliding, 3);
  // Measured: 22.1k box tests against 38.4k from the roots.
  EXPECT_LT(cut_counters.box_tests, root_counters.box_tests * 3 / 4)
      << cut_counters.box_tests << " vs " << root_counters.box_tests;
  // From elsewhere: the roots, test for test.
  ProximityCounters far_cut, far_roots;
  with.counters = &far_cut;
  counted.counters = &far_roots;
  const Vector3 far = 0.1 * with.size() * Vector3(0.0, 0.0, 1.0);
  std::vector<ContactConstraint> a, b;
  CollectContactConstraints(with, far, distance, &a);
  CollectContactConstraints(counted, far, distance, &b);
  EXPECT_EQ(keys(a), keys(b));
  EXPECT_EQ(far_cut.box_tests, far_roots.box_tests);
}

}  // namespace
}  // namespace pd
