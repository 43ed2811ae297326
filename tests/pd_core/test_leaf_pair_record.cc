// A record of the leaf pairs near a configuration (leaf_pair_record.h): the
// ball of configurations it answers for, a localisation that records its
// leaf pairs (contact_constraints.h), and the collision tests inside that
// ball that walk it instead of descending. References are brute force over
// all triangle pairs (brute_force_pairs.h) and the full BVH descent.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "pd_core/geometry/make_shapes.h"
#include "pd_core/polydepth/contact_constraints.h"
#include "pd_core/polydepth/support_plane_starts.h"
#include "pd_core/proximity/candidate_pairs.h"
#include "pd_core/proximity/leaf_pair_record.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"
#include "pd_core/proximity/translational_ccd.h"
#include "tests/pd_core/brute_force_pairs.h"

namespace pd {
namespace {

TEST(LeafPairRecord, AnswersForTheBallItsDistanceLeaves) {
  LeafPairRecord record;
  record.distance = 1e-3;
  const Vector3 q(0.02, -0.01, 0.03), u = Vector3(1, 2, -2) / 3.0;
  EXPECT_FALSE(record.Covers(q, q, 0.0));  // not made yet
  record.q_S = q;
  record.valid = true;
  EXPECT_TRUE(record.Covers(q, q, 1e-3));
  EXPECT_FALSE(record.Covers(q, q, 1.01e-3));
  // A point 0.4 mm off: pairs within 0.6 mm there were within 1 mm at q.
  EXPECT_TRUE(record.Covers(q + 4e-4 * u, q + 4e-4 * u, 5.99e-4));
  EXPECT_FALSE(record.Covers(q + 4e-4 * u, q + 4e-4 * u, 6.01e-4));
  // A segment: its farther end decides.
  EXPECT_TRUE(record.Covers(q - 1e-4 * u, q + 3e-4 * u, 6.99e-4));
  EXPECT_FALSE(record.Covers(q - 1e-4 * u, q + 3e-4 * u, 7.01e-4));
  EXPECT_FALSE(record.Covers(q, q + 1.01e-3 * u, 0.0));
  record.Invalidate();
  EXPECT_FALSE(record.Covers(q, q, 0.0));
}

// An icosphere probe touching a torus knot from outside: the landing point
// of a CCD from a free support-plane start toward a colliding pose.
struct TouchingPair {
  std::shared_ptr<const CollisionModel> P = CollisionModel::Build(MakeIcosphere(0.3, 3));
  std::shared_ptr<const CollisionModel> S =
      CollisionModel::Build(MakeTorusKnot(2, 3, 0.2, 1.0, 96, 12));
  Isometry3 X_WP = Isometry3::Identity();
  Vector3 q_c = Vector3::Zero();

  explicit TouchingPair(int seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g;
    const auto& V = S->mesh().vertices;
    for (;;) {
      X_WP.linear() = Quaternion(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
      X_WP.translation() = V[rng() % V.size()] + 0.1 * Vector3(g(rng), g(rng), g(rng));
      if (InCollision(Pair(), Vector3::Zero())) break;
    }
    const ModelPair pair = Pair();
    std::vector<SupportPlaneStart> starts;
    ComputeSupportPlaneStarts(pair, 48, &starts);
    const Vector3 from = starts[0].q_S;
    const double s = FirstContactAlongTranslation(pair, from, -from);
    q_c = from - (s - 1e-8 * pair.size() / from.norm()) * from;
  }
  ModelPair Pair() const { return ModelPair(*P, *S, X_WP, Isometry3::Identity()); }
  // A localisation's record at the contact, of distance 1e-3 of the size.
  LeafPairRecord RecordAtContact() const {
    const ModelPair pair = Pair();
    LeafPairRecord record;
    record.distance = 1e-3 * pair.size();
    std::vector<ContactConstraint> cs;
    CollectContactConstraints(pair, q_c, record.distance, &cs, &record);
    return record;
  }
};

// A localisation asked to record keeps every leaf pair within the record's
// distance at its configuration (farther than its own), whichever way it
// found them; it is then the record there.
TEST(LeafPairRecord, ALocalisationRecordsEveryLeafPairWithinTheRecordsDistance) {
  int near_pairs = 0;
  for (int seed : {1, 2, 3}) {
    const TouchingPair t(seed);
    const ModelPair pair = t.Pair();
    ASSERT_FALSE(InCollision(pair, t.q_c)) << "seed " << seed;
    const double d = 1e-4 * pair.size();
    LeafPairRecord record;
    record.distance = 300.0 * d;
    std::vector<ContactConstraint> cs;
    CollectContactConstraints(pair, t.q_c, d, &cs, &record);
    ASSERT_TRUE(record.valid);
    EXPECT_EQ(record.q_S, t.q_c);
    EXPECT_FALSE(cs.empty());
    std::vector<std::pair<int, int>> recorded;
    for (const auto& e : record.pairs) recorded.push_back({e.ip, e.is});
    std::sort(recorded.begin(), recorded.end());
    const std::vector<int> leaf_P = test::LeafOfTriangle(t.P->bvh(), t.P->mesh().num_triangles());
    const std::vector<int> leaf_S = test::LeafOfTriangle(t.S->bvh(), t.S->mesh().num_triangles());
    test::ForEachTrianglePairWithin(pair, t.q_c, record.distance, [&](int tp, int ts) {
      ++near_pairs;
      EXPECT_TRUE(std::binary_search(recorded.begin(), recorded.end(),
                                     std::make_pair(leaf_P[tp], leaf_S[ts])))
          << "seed " << seed << " triangles " << tp << ", " << ts;
    });
    // Asked again where the record answers already, it leaves it as it is.
    const size_t n = record.pairs.size();
    record.pairs.push_back({-1, -1});  // a marker a new recording would clear
    CollectContactConstraints(pair, t.q_c + 0.5 * d * Vector3::UnitX(), d, &cs, &record);
    EXPECT_EQ(record.pairs.size(), n + 1);
    EXPECT_EQ(record.q_S, t.q_c);
  }
  EXPECT_GT(near_pairs, 30);
}

// Collision tests at configurations inside the record's ball walk its pairs
// and answer as a full descent does, for fewer box tests; outside the ball
// the record does not answer.
TEST(LeafPairRecord, CollisionTestsInsideTheBallWalkItAndAnswerAsADescent) {
  int colliding = 0, free = 0;
  ProximityCounters walked, descended;
  for (int seed : {4, 5, 6}) {
    const TouchingPair t(seed);
    ModelPair pair = t.Pair();
    const LeafPairRecord record = t.RecordAtContact();
    ASSERT_TRUE(record.valid);
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g;
    std::uniform_real_distribution<double> frac(0.0, 1.0);
    for (int k = 0; k < 60; ++k) {
      const Vector3 u = Vector3(g(rng), g(rng), g(rng)).normalized();
      const Vector3 q = t.q_c + frac(rng) * record.distance * u;
      ASSERT_TRUE(record.Covers(q, q, 0.0));
      pair.recorded = nullptr;
      pair.counters = &descended;
      const bool by_descent = InCollision(pair, q);
      pair.recorded = &record;
      pair.counters = &walked;
      EXPECT_EQ(InCollision(pair, q), by_descent) << "seed " << seed << " point " << k;
      (by_descent ? colliding : free)++;
      const Vector3 beyond = t.q_c + (1.0 + 2.0 * frac(rng)) * record.distance * u;
      EXPECT_FALSE(record.Covers(beyond, beyond, 0.0));
    }
  }
  EXPECT_GT(colliding, 20);
  EXPECT_GT(free, 20);
  EXPECT_LT(walked.box_tests, descended.box_tests / 2)
      << walked.box_tests << " vs " << descended.box_tests;
}

// Where a candidate list covers too, a check walks whichever of the two
// holds fewer pairs: the record beside a list built before the probe turned
// by 3 degrees (the turn bounds every entry's motion: its near prefix holds
// many entries, few of them skipped along their axes), a narrow list built
// here beside the record. Both answer as a descent does.
TEST(LeafPairRecord, BesideAListTheSmallerOfTheTwoIsWalked) {
  const TouchingPair t(7);
  ModelPair pair = t.Pair();
  const LeafPairRecord record = t.RecordAtContact();
  ASSERT_TRUE(record.valid);
  CandidatePairs wide, narrow;
  Isometry3 X_WP_before = t.X_WP;
  X_WP_before.linear() =
      Eigen::AngleAxisd(3.0 * M_PI / 180.0, Vector3(1, 1, 0).normalized()).toRotationMatrix() *
      t.X_WP.linear();
  wide.Build(ModelPair(*t.P, *t.S, X_WP_before, Isometry3::Identity()), t.q_c,
             0.05 * pair.size());
  narrow.Build(pair, t.q_c, 2e-4 * pair.size());
  ASSERT_GT(wide.entries().size(), 2 * record.pairs.size());
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  int64_t wide_tests = 0, narrow_tests = 0;
  int colliding = 0;
  const int points = 20;
  for (int k = 0; k < points; ++k) {
    const Vector3 q = t.q_c + 1e-4 * pair.size() * Vector3(g(rng), g(rng), g(rng)).normalized();
    pair.recorded = nullptr;
    pair.candidates = nullptr;
    const bool by_descent = InCollision(pair, q);
    colliding += by_descent;
    pair.recorded = &record;
    for (const CandidatePairs* list : {&wide, &narrow}) {
      pair.candidates = list;
      ProximityCounters counters;
      pair.counters = &counters;
      EXPECT_EQ(InCollision(pair, q), by_descent) << "point " << k;
      (list == &wide ? wide_tests : narrow_tests) += counters.box_tests;
      pair.counters = nullptr;
    }
  }
  EXPECT_GT(colliding, 0);
  EXPECT_LT(colliding, points);
  // A record walk tests each of its pairs at most once (a collision test
  // stops at the first intersecting pair); the narrow list holds fewer.
  // Measured: 795 box tests beside the turned list (1340 walking that
  // list), 495 with the narrow list, against 940 for 20 record walks.
  const int64_t record_walks = points * static_cast<int64_t>(record.pairs.size());
  EXPECT_LE(wide_tests, record_walks);
  EXPECT_LT(narrow_tests, record_walks);
}

// A fused localisation that meets an intersecting triangle pair has not
// seen every pair: its record is not valid.
TEST(LeafPairRecord, ALocalisationStoppedByAnIntersectionLeavesNoRecord) {
  const TouchingPair t(7);
  const ModelPair pair = t.Pair();
  LeafPairRecord record;
  record.distance = 1e-4 * pair.size();
  record.q_S = t.q_c;
  record.valid = true;  // an earlier record elsewhere
  std::vector<ContactConstraint> cs;
  EXPECT_FALSE(CollectContactConstraintsIfSurfacesFree(pair, Vector3::Zero(), record.distance,
                                                        &cs, nullptr, &record));
  EXPECT_FALSE(record.valid);
  // At the free landing point it records.
  EXPECT_TRUE(
      CollectContactConstraintsIfSurfacesFree(pair, t.q_c, record.distance, &cs, nullptr, &record));
  EXPECT_TRUE(record.valid);
  EXPECT_EQ(record.q_S, t.q_c);
}

}  // namespace
}  // namespace pd
