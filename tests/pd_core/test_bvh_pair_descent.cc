// The one BVH pair descent (pd_core/proximity/bvh_pair_descent.h): it visits exactly
// the leaf pairs a brute-force sweep keeps, in any tree shape, including
// trees deeper than its fixed stack (which once overflowed silently), and
// depth is measured from the links, not trusted. Best-first order visits the
// same pairs, lowest key first, also when its fixed heap fills up. A
// depth-first descent run in pieces (ContinueBvhPairDescent, a list built in
// idle time) visits the same pairs in the same order as one uninterrupted.
#include <gtest/gtest.h>

#include <tuple>

#include <algorithm>
#include <set>
#include <utility>

#include "pd_core/proximity/bvh_pair_descent.h"
#include "tests/pd_core/synthetic_bvh.h"

namespace pd {
namespace {

using test::Balanced;
using test::Caterpillar;
using test::Overlap;

// The leaf pairs whose boxes overlap, in the order one depth-first descent
// visits them.
std::vector<std::pair<int, int>> OverlappingLeafPairsInOrder(const Bvh& a, const Bvh& b,
                                                             ProximityCounters* counters) {
  std::vector<std::pair<int, int>> visited;
  DescendBvhPair(
      a, b,
      [](const BvhNode& x, const BvhNode& y, double* key) {
        *key = 0.0;
        return Overlap(x, y);
      },
      [](double) { return true; },
      [&](int ip, int is) {
        visited.push_back({ip, is});
        return true;
      },
      counters);
  return visited;
}

TEST(BvhPairDescent, DepthIsMeasuredFromTheLinks) {
  EXPECT_EQ(Caterpillar(1, 0.0).depth(), 1);
  EXPECT_EQ(Caterpillar(2, 0.0).depth(), 2);
  EXPECT_EQ(Caterpillar(300, 0.0).depth(), 300);
}

TEST(BvhPairDescent, TreesDeeperThanTheFixedStackVisitExactlyTheOverlappingLeafPairs) {
  // 300 + 300 levels: needs a stack of ~600 entries, more than the fixed one.
  const Bvh a = Caterpillar(300, 0.0), b = Caterpillar(300, 0.5);
  ASSERT_GT(a.depth() + b.depth() + 1, kDescentStackCapacity);
  ProximityCounters counters;
  const std::vector<std::pair<int, int>> in_order = OverlappingLeafPairsInOrder(a, b, &counters);
  const std::set<std::pair<int, int>> visited(in_order.begin(), in_order.end());
  EXPECT_EQ(visited.size(), in_order.size()) << "a leaf pair visited twice";
  std::set<std::pair<int, int>> expected;
  for (int i = 0; i < static_cast<int>(a.nodes().size()); ++i)
    for (int j = 0; j < static_cast<int>(b.nodes().size()); ++j)
      if (a.nodes()[i].is_leaf() && b.nodes()[j].is_leaf() && Overlap(a.nodes()[i], b.nodes()[j]))
        expected.insert({i, j});
  EXPECT_EQ(visited, expected);
  EXPECT_GT(counters.box_tests, 0);
}

TEST(BvhPairDescent, KeysOrderTheVisitAndAliveDropsPairsWhenPopped) {
  const Bvh a = Caterpillar(40, 0.0), b = Caterpillar(40, 0.0);
  // Key: the node pair's x distance from x = 20; stop at the first leaf pair.
  std::vector<std::pair<int, int>> visited;
  DescendBvhPair(
      a, b,
      [](const BvhNode& x, const BvhNode& y, double* key) {
        *key = std::abs(x.center_M.x() - 20.0) + std::abs(y.center_M.x() - 20.0);
        return Overlap(x, y);
      },
      [](double key) { return key < 1e9; },
      [&](int ip, int is) {
        visited.push_back({ip, is});
        return false;  // stop the descent
      });
  ASSERT_EQ(visited.size(), 1u);
}

// Leaf pairs visited in order, with their keys.
template <DescentOrder kOrder>
std::vector<std::pair<std::pair<int, int>, double>> Visit(const Bvh& a, const Bvh& b,
                                                          ProximityCounters* counters) {
  std::vector<std::pair<std::pair<int, int>, double>> visited;
  DescendBvhPair<kOrder>(
      a, b,
      [](const BvhNode& x, const BvhNode& y, double* key) {
        // A key no lower than the parent's: the node pair's distance from x = 5.
        *key = std::max(*key, std::abs(x.center_M.x() - 5.0) - x.half_B.x() +
                                  std::abs(y.center_M.x() - 5.0) - y.half_B.x());
        return Overlap(x, y);
      },
      [](double) { return true; },
      [&](int ip, int is, double key) {
        visited.push_back({{ip, is}, key});
        return true;
      },
      counters);
  return visited;
}

TEST(BvhPairDescent, BestFirstVisitsTheSameLeafPairsLowestKeyFirst) {
  for (const auto& [a, b] : {std::pair(Caterpillar(300, 0.0), Caterpillar(300, 0.5)),
                             std::pair(Balanced(6, 1.0), Balanced(6, 0.7)),
                             // 64 x 64 leaf pairs all overlapping: more pending pairs than
                             // the heap holds, the depth-first fallback runs.
                             std::pair(Balanced(6, 0.0), Balanced(6, 0.0))}) {
    ProximityCounters df_count, bf_count;
    const auto df = Visit<DescentOrder::kDepthFirst>(a, b, &df_count);
    const auto bf = Visit<DescentOrder::kBestFirst>(a, b, &bf_count);
    std::set<std::pair<int, int>> df_pairs, bf_pairs;
    for (const auto& v : df) EXPECT_TRUE(df_pairs.insert(v.first).second);
    for (const auto& v : bf) EXPECT_TRUE(bf_pairs.insert(v.first).second) << "visited twice";
    EXPECT_FALSE(bf_pairs.empty());
    EXPECT_EQ(bf_pairs, df_pairs);
    EXPECT_EQ(bf_count.box_tests, df_count.box_tests);  // alive always true: same expansions
    if (bf.size() < static_cast<size_t>(kBestFirstHeapCapacity)) {
      for (size_t i = 1; i < bf.size(); ++i) EXPECT_LE(bf[i - 1].second, bf[i].second) << i;
    }
  }
  EXPECT_EQ(Visit<DescentOrder::kBestFirst>(Balanced(6, 0.0), Balanced(6, 0.0), nullptr).size(),
            4096u);
}

TEST(BvhPairDescent, BestFirstEndsAtTheFirstPairNotAlive) {
  const Bvh a = Balanced(6, 1.0), b = Balanced(6, 1.0);
  // Keys: distance from x = 20; alive below 3: only pairs near x = 20 are visited.
  std::vector<double> keys;
  ProximityCounters all, limited;
  DescendBvhPair<DescentOrder::kBestFirst>(
      a, b,
      [](const BvhNode& x, const BvhNode& y, double* key) {
        *key = std::max(*key, std::abs(x.center_M.x() - 20.0) - x.half_B.x());
        return Overlap(x, y);
      },
      [](double key) { return key < 3.0; },
      [&](int, int, double key) {
        keys.push_back(key);
        return true;
      },
      &limited);
  Visit<DescentOrder::kBestFirst>(a, b, &all);
  ASSERT_FALSE(keys.empty());
  for (double k : keys) EXPECT_LT(k, 3.0);
  EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
  EXPECT_LT(limited.box_tests, all.box_tests / 4);
}


// A best-first descent stopped by the caller (bounded-time CCD) reports the
// lowest pending key: a lower bound on the key of every leaf pair it did not
// reach. Checked against the full descent's leaf keys.
TEST(BvhPairDescent, BestFirstStoppedReportsALowerBoundOnEveryLeafNotReached) {
  const Bvh a = Balanced(6, 1.0), b = Balanced(6, 1.0);
  auto key_from_20 = [](const BvhNode& x, const BvhNode& y, double* key) {
    *key = std::max(*key, std::abs(x.center_M.x() - 20.0) - x.half_B.x());
    return Overlap(x, y);
  };
  std::vector<std::tuple<int, int, double>> all;
  DescendBvhPair<DescentOrder::kBestFirst>(
      a, b, key_from_20, [](double) { return true; },
      [&](int ip, int is, double key) {
        all.emplace_back(ip, is, key);
        return true;
      });
  ASSERT_GT(all.size(), 20u);
  for (int stop_after : {1, 5, 40}) {
    std::vector<std::pair<int, int>> reached;
    int asked = 0;
    double stopped_at = 1e300;
    DescendBvhPair<DescentOrder::kBestFirst>(
        a, b, key_from_20, [](double) { return true; },
        [&](int ip, int is) {
          reached.emplace_back(ip, is);
          return true;
        },
        nullptr, 0, 0, [&] { return ++asked > stop_after; }, &stopped_at);
    EXPECT_EQ(asked, stop_after + 1);  // asked before each pop until it says stop
    ASSERT_LT(stopped_at, 1e300) << stop_after;
    int not_reached = 0;
    for (const auto& [ip, is, key] : all) {
      if (std::find(reached.begin(), reached.end(), std::make_pair(ip, is)) != reached.end()) continue;
      ++not_reached;
      EXPECT_GE(key, stopped_at) << stop_after;
    }
    EXPECT_GT(not_reached, 0) << stop_after;
  }
  // Never stopped: *stopped_at untouched.
  double untouched = 7.0;
  DescendBvhPair<DescentOrder::kBestFirst>(
      a, b, key_from_20, [](double) { return true; }, [](int, int) { return true; }, nullptr, 0, 0,
      [] { return false; }, &untouched);
  EXPECT_EQ(untouched, 7.0);
}

// Leaf pairs of a depth-first descent run in pieces, pausing after every
// `stride` pairs visited; *calls gets how many calls it took.
std::vector<std::pair<int, int>> VisitInPieces(const Bvh& a, const Bvh& b, int stride,
                                               ProximityCounters* counters, int* calls) {
  std::vector<std::pair<int, int>> visited;
  DescentCursor cursor;
  EXPECT_FALSE(cursor.started());
  int visits = 0;
  *calls = 0;
  for (;;) {
    ++*calls;
    const bool done = ContinueBvhPairDescent(
        a, b,
        [](const BvhNode& x, const BvhNode& y, double* key) {
          *key = 0.0;
          return Overlap(x, y);
        },
        [&](int ip, int is) {
          visited.push_back({ip, is});
          return true;
        },
        [&] { return ++visits % stride == 0; }, &cursor, counters);
    EXPECT_EQ(done, cursor.done());
    if (done) break;
    if (*calls > 100000) {
      ADD_FAILURE() << "no end";
      break;
    }
  }
  return visited;
}

TEST(BvhPairDescent, ADescentInPiecesVisitsWhatOneDescentVisitsInTheSameOrder) {
  for (const auto& [a, b] : {std::pair(Caterpillar(300, 0.0), Caterpillar(300, 0.5)),
                             std::pair(Balanced(6, 1.0), Balanced(6, 0.7)),
                             std::pair(Balanced(5, 0.0), Balanced(5, 0.0))}) {
    ProximityCounters whole_count;
    const std::vector<std::pair<int, int>> whole = OverlappingLeafPairsInOrder(a, b, &whole_count);
    ASSERT_FALSE(whole.empty());
    for (int stride : {1, 7, 1000000}) {
      ProximityCounters count;
      int calls = 0;
      EXPECT_EQ(VisitInPieces(a, b, stride, &count, &calls), whole) << "stride " << stride;
      EXPECT_EQ(count.box_tests, whole_count.box_tests) << "stride " << stride;
      // Pausing after every pair: one call per pair visited, about.
      if (stride == 1) EXPECT_GT(calls, static_cast<int>(whole.size()));
      if (stride == 1000000) EXPECT_EQ(calls, 1);
    }
  }
}

TEST(BvhPairDescent, AResetCursorStartsAgainAtTheRoots) {
  const Bvh a = Balanced(5, 1.0), b = Balanced(5, 0.7);
  DescentCursor cursor;
  std::vector<std::pair<int, int>> visited;
  auto test = [](const BvhNode& x, const BvhNode& y, double* key) {
    *key = 0.0;
    return Overlap(x, y);
  };
  auto leaf = [&](int ip, int is) {
    visited.push_back({ip, is});
    return true;
  };
  // A few pieces, then a reset: the next run is a whole descent of its own.
  for (int k = 0; k < 5; ++k) ContinueBvhPairDescent(a, b, test, leaf, [] { return true; }, &cursor, nullptr);
  ASSERT_FALSE(cursor.done());
  cursor.Reset();
  visited.clear();
  EXPECT_TRUE(ContinueBvhPairDescent(a, b, test, leaf, [] { return false; }, &cursor, nullptr));
  int calls = 0;
  ProximityCounters count;
  EXPECT_EQ(visited, VisitInPieces(a, b, 1000000, &count, &calls));
}

}  // namespace
}  // namespace pd
