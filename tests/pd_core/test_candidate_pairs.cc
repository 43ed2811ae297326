// The leaf-pair and twig-pair lists (pd_core/proximity/candidate_pairs.h) as
// the queries walk them (leaf_pairs_near.h): at configurations moved and turned away from where
// it was built, the walk must reach every triangle pair within the query's
// distance that a full descent reaches, although it skips the entries whose
// stored separating axis proves them apart without a box test. And on a real
// mesh path the skipping must pay: fewer box tests than walking the prefix.
// A list built in pieces (a geometry thread's idle time) is the list of one
// build, and not valid before it is complete.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <utility>

#include "pd_core/mesh/load_mesh.h"
#include "pd_core/proximity/box_overlap.h"
#include "pd_core/proximity/candidate_pairs.h"
#include "pd_core/proximity/leaf_pairs_near.h"
#include "pd_core/proximity/model_pair.h"
#include "pd_core/proximity/triangle_geometry.h"
#include "tests/prerequisites.h"
#include "tests/pd_core/brute_force_pairs.h"
#include "tests/pd_core/fandisk_on_elephant.h"
#include "tests/pd_core/scaled_mesh_model.h"

namespace pd {
namespace {

using test::LoadScaled;

using test::TriangleDistance;

using TrianglePairs = std::set<std::pair<int, int>>;

// The triangle pairs within `distance` with the probe translated by q_S,
// from the pair's list when it covers q_S, else from a descent.
TrianglePairs PairsWithin(const ModelPair& pair, const Vector3& q_S, double distance) {
  TrianglePairs out;
  ForEachLeafPairNear(
      pair, q_S, q_S, distance,
      [&](const BvhNode& a, const BvhNode& b) {
        return BoxesWithin(ProbeBox(a, pair.X_SP, q_S), b, distance);
      },
      [&](int ip, int is) {
        return ForEachTrianglePair(pair.P.bvh(), pair.S.bvh(), ip, is, [&](int tp, int ts) {
          Vector3 a[3], b[3];
          pair.ProbeTriangle(tp, q_S, a);
          pair.SceneTriangle(ts, b);
          if (TriangleDistance(a, b) <= distance) out.insert({tp, ts});
          return true;
        });
      });
  return out;
}

// A pose of bench_pd's fandisk_elephant haptic path (pose 1200: the tool
// 2 mm deep in the object), tool and object scaled as there; lists of the
// radius and queries of the distance PolyDepth uses (3.6e-3 and 1e-4 of the
// pair's size).
class CandidatePairsFandiskOnElephant : public test::FandiskOnElephant {
 protected:
  void SetUp() override {
    FandiskOnElephant::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    const double size = PairAt(Vector3::Zero(), 0.0, Vector3::UnitZ()).size();
    radius = 3.6e-3 * size;
    distance = 1e-4 * size;
  }
  // The pose moved by p_W and turned by turn_rad about axis_W.
  ModelPair PairAt(const Vector3& p_W, double turn_rad, const Vector3& axis_W) const {
    Isometry3 X_WP = Isometry3::Identity();
    X_WP.linear() =
        (Eigen::AngleAxisd(turn_rad, axis_W.normalized()) * Pose1200Rotation()).toRotationMatrix();
    X_WP.translation() = Pose1200Position() + p_W;
    return ModelPair(*tool, *object, X_WP, Isometry3::Identity());
  }
  double radius = 0.0, distance = 0.0;
};

class CandidatePairsGrain : public CandidatePairsFandiskOnElephant,
                           public ::testing::WithParamInterface<CandidatePairs::Grain> {};

TEST_P(CandidatePairsGrain, ListWalkReachesEveryTrianglePairADescentReachesAfterMotion) {
  const ModelPair built = PairAt(Vector3::Zero(), 0.0, Vector3::UnitZ());
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  auto unit = [&] { return Vector3(g(rng), g(rng), g(rng)).normalized(); };
  int compared = 0, nonempty = 0;
  for (int trial = 0; trial < 6; ++trial) {
    // Around configurations where the surfaces meet or nearly do (offsets
    // of up to 3 mm in any direction from the pose 2 mm deep).
    const Vector3 q_build_S =
        3e-3 * std::uniform_real_distribution<double>(0.0, 1.0)(rng) * unit();
    CandidatePairs list;
    list.Build(built, q_build_S, radius, GetParam());
    if (list.entries().empty()) continue;
    for (int k = 0; k < 40; ++k) {
      // Moved and turned since the build: the pose's own motion and an
      // extra translation q_S, together inside the list's reach.
      const double turn = 1e-3 * g(rng);
      ModelPair pair = PairAt(0.25 * radius * unit(), turn, unit());
      const Vector3 q_S = q_build_S + 0.3 * radius * unit();
      pair.candidates = &list;
      if (list.Displacement(pair, q_S) + distance >= list.radius()) continue;
      const TrianglePairs from_list = PairsWithin(pair, q_S, distance);
      pair.candidates = nullptr;
      const TrianglePairs from_descent = PairsWithin(pair, q_S, distance);
      EXPECT_EQ(from_list, from_descent) << "trial " << trial << " move " << k;
      ++compared;
      nonempty += !from_descent.empty();
    }
  }
  // The moves stay inside the list and many of them touch the surface.
  EXPECT_GE(compared, 150);
  EXPECT_GE(nonempty, 30);
}


TEST_P(CandidatePairsGrain, ABuildInPiecesIsTheBuildInOneAndInvalidUntilComplete) {
  const ModelPair pair = PairAt(Vector3::Zero(), 0.0, Vector3::UnitZ());
  ProximityCounters one_count, pieces_count;
  ModelPair counted = pair;
  counted.counters = &one_count;
  CandidatePairs one;
  one.Build(counted, Vector3::Zero(), radius, GetParam());
  ASSERT_TRUE(one.valid());
  ASSERT_GT(one.entries().size(), 100u);

  CandidatePairs pieces;
  pieces.BeginBuild(pair, Vector3::Zero(), radius, GetParam());
  EXPECT_TRUE(pieces.building());
  EXPECT_FALSE(pieces.valid());
  EXPECT_EQ(pieces.BuildWillCover(pair, Vector3::Zero(), 0.0), true);
  EXPECT_EQ(pieces.BuildWillCover(pair, Vector3(2.0 * radius, 0, 0), 0.0), false);
  int calls = 0;
  int64_t most = 0;
  for (;;) {
    ++calls;
    const int64_t before = pieces_count.box_tests;
    // Always asked to stop: each call does a few dozen pairs' work.
    const bool done = pieces.ContinueBuild([] { return true; }, &pieces_count);
    most = std::max(most, pieces_count.box_tests - before);
    if (done) break;
    EXPECT_FALSE(pieces.valid());
    EXPECT_FALSE(pieces.Covers(pair, Vector3::Zero(), Vector3::Zero(), 0.0));
    ASSERT_LT(calls, 1000000);
  }
  EXPECT_GT(calls, 10);
  EXPECT_LE(most, 200);  // the stride's pairs, each two box tests and a full test
  EXPECT_TRUE(pieces.valid());
  EXPECT_FALSE(pieces.building());
  EXPECT_TRUE(pieces.Covers(pair, Vector3::Zero(), Vector3::Zero(), 0.0));
  EXPECT_EQ(pieces_count.box_tests, one_count.box_tests);
  EXPECT_EQ(pieces_count.by_kind[static_cast<int>(QueryKind::kListBuild)],
            one_count.by_kind[static_cast<int>(QueryKind::kListBuild)]);
  ASSERT_EQ(pieces.entries().size(), one.entries().size());
  for (size_t i = 0; i < one.entries().size(); ++i) {
    EXPECT_EQ(pieces.entries()[i].ip, one.entries()[i].ip) << i;
    EXPECT_EQ(pieces.entries()[i].is, one.entries()[i].is) << i;
    EXPECT_EQ(pieces.entries()[i].gap, one.entries()[i].gap) << i;
  }
  // Invalidate drops a build under way: nothing more to continue.
  pieces.BeginBuild(pair, Vector3::Zero(), radius, GetParam());
  pieces.ContinueBuild([] { return true; }, nullptr);
  pieces.Invalidate();
  EXPECT_FALSE(pieces.building());
  EXPECT_FALSE(pieces.ContinueBuild([] { return false; }, nullptr));
  EXPECT_FALSE(pieces.valid());
}

INSTANTIATE_TEST_SUITE_P(LeafAndTwigPairs, CandidatePairsGrain,
                         ::testing::Values(CandidatePairs::Grain::kLeafPairs,
                                           CandidatePairs::Grain::kTwigPairs),
                         [](const auto& info) {
                           return info.param == CandidatePairs::Grain::kLeafPairs ? "LeafPairs"
                                                                                  : "TwigPairs";
                         });

// A twig-pair list pairs twigs only, stops its build above the leaves on
// this dense patch (fewer box tests and entries than the leaf-pair list of
// the same reach) and still holds every leaf pair of that list inside one
// of its entries.
TEST_F(CandidatePairsFandiskOnElephant, TwigPairListCoversTheLeafPairListWithFewerEntries) {
  const ModelPair pair = PairAt(Vector3::Zero(), 0.0, Vector3::UnitZ());
  ProximityCounters leaf_work, twig_work;
  ModelPair counted = pair;
  CandidatePairs leaf, twig;
  counted.counters = &leaf_work;
  leaf.Build(counted, Vector3::Zero(), radius, CandidatePairs::Grain::kLeafPairs);
  counted.counters = &twig_work;
  twig.Build(counted, Vector3::Zero(), radius, CandidatePairs::Grain::kTwigPairs);
  ASSERT_GT(leaf.entries().size(), 500u);
  EXPECT_LT(twig.entries().size(), leaf.entries().size());
  EXPECT_LT(twig_work.box_tests, leaf_work.box_tests);
  const auto& nodes_P = pair.P.bvh().nodes();
  const auto& nodes_S = pair.S.bvh().nodes();
  // The leaves under a node: its index range in depth-first storage.
  auto subtree_end = [](const std::vector<BvhNode>& nodes, int32_t i) {
    while (!nodes[i].is_leaf()) i = nodes[i].right_or_first;
    return i + 1;
  };
  std::set<std::pair<int, int>> covered;
  size_t above_leaves = 0;
  for (const CandidatePairs::Entry& e : twig.entries()) {
    ASSERT_TRUE(IsTwig(nodes_P, e.ip, CandidatePairs::kProbeTwigLevels) &&
                IsTwig(nodes_S, e.is, CandidatePairs::kSceneTwigLevels));
    above_leaves += !(nodes_P[e.ip].is_leaf() && nodes_S[e.is].is_leaf());
    for (int ip = e.ip; ip < subtree_end(nodes_P, e.ip); ++ip)
      for (int is = e.is; is < subtree_end(nodes_S, e.is); ++is)
        if (nodes_P[ip].is_leaf() && nodes_S[is].is_leaf()) covered.insert({ip, is});
  }
  EXPECT_GT(above_leaves, twig.entries().size() / 2);
  for (const CandidatePairs::Entry& e : leaf.entries())
    EXPECT_TRUE(covered.count({e.ip, e.is})) << e.ip << " " << e.is;
}

TEST_F(CandidatePairsFandiskOnElephant, SeparatingAxesSpareMostBoxTestsOfAWalkAfterMotion) {
  // Built at the pose itself, where the surfaces cross along a long curve;
  // then walked at configurations moved by half the list's reach (two to
  // three ticks of the benchmark's paths), in fixed random directions.
  ModelPair pair = PairAt(Vector3::Zero(), 0.0, Vector3::UnitZ());
  CandidatePairs list;
  list.Build(pair, Vector3::Zero(), radius);
  ProximityCounters counters;
  pair.candidates = &list;
  pair.counters = &counters;
  int64_t tested = 0, prefix = 0;
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  for (int k = 0; k < 20; ++k) {
    const Vector3 q_S = 0.5 * radius * Vector3(g(rng), g(rng), g(rng)).normalized();
    ASSERT_LT(list.Displacement(pair, q_S) + distance, list.radius());
    counters = ProximityCounters{};
    PairsWithin(pair, q_S, distance);
    tested += counters.box_tests;
    prefix += list.NearCount(distance, list.Displacement(pair, q_S));
  }
  ASSERT_GT(prefix, 1000);
  // Without the axes every entry of the prefix costs a box test.
  EXPECT_LT(tested, prefix / 2) << tested << " box tests for " << prefix << " prefix entries";
}

}  // namespace
}  // namespace pd
