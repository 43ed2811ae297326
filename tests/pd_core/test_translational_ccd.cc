// Translational CCD (pd_core/proximity/translational_ccd.h) on real meshes:
// its first contact equals a brute force over all triangle pairs (no BVH),
// and the best-first order of the shared descent finds the same contact
// with fewer box tests than depth-first on long sweeps.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "pd_core/polydepth/contact_constraints.h"
#include "pd_core/polydepth/support_plane_starts.h"
#include "pd_core/proximity/candidate_pairs.h"
#include "pd_core/proximity/descent_front.h"
#include "pd_core/proximity/leaf_pair_record.h"
#include "pd_core/proximity/box_overlap.h"
#include "pd_core/proximity/bvh_pair_descent.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"
#include "pd_core/proximity/translational_ccd.h"
#include "pd_core/proximity/triangle_geometry.h"
#include "tests/pd_core/brute_force_pairs.h"
#include "tests/prerequisites.h"

namespace pd {
namespace {

using Model = std::shared_ptr<const CollisionModel>;
const std::string kMeshDir = PD_TEST_MESH_DIR;

// Earliest contact in [0, 1] of probe triangle tp (at offset_S + s sweep_S)
// with scene triangle ts over all 6 vertex-face and 9 edge-edge events; 2
// when none.
double TrianglePairContact(const ModelPair& pair, int tp, int ts, const Vector3& offset_S,
                           const Vector3& sweep_S) {
  Vector3 p[3], s[3];
  pair.ProbeTriangle(tp, offset_S, p);
  pair.SceneTriangle(ts, s);
  double best = 2.0;
  auto take = [&](double t) {
    if (t >= 0.0 && t <= 1.0) best = std::min(best, t);
  };
  for (int k = 0; k < 3; ++k) {
    take(RayTriangle(p[k], sweep_S, s[0], s[1], s[2], 1.0));
    take(RayTriangle(s[k], -sweep_S, p[0], p[1], p[2], 1.0));
    for (int j = 0; j < 3; ++j)
      take(EdgeEdgeTranslationalContact(p[k], p[(k + 1) % 3], s[j], s[(j + 1) % 3], sweep_S, 1.0));
  }
  return best;
}

// Brute force: every triangle pair whose swept boxes overlap, no BVH. -1
// when free.
double BruteForceFirstContact(const ModelPair& pair, const Vector3& offset_S,
                              const Vector3& sweep_S) {
  double best = 2.0;
  test::ForEachOverlappingTrianglePair(pair, offset_S, sweep_S, [&](int tp, int ts) {
    best = std::min(best, TrianglePairContact(pair, tp, ts, offset_S, sweep_S));
    return true;
  });
  return best <= 1.0 ? best : -1.0;
}

// The CCD's descent written out with a chosen order: swept-box intervals as
// keys, pairs later than the best contact dropped, leaf triangle pairs by
// TrianglePairContact. Returns the first contact (-1 when free).
template <DescentOrder kOrder>
double DescentFirstContact(const ModelPair& pair, const Vector3& offset_S, const Vector3& sweep_S,
                           ProximityCounters* counters) {
  double s_best = 1.0;
  bool hit = false;
  const SweepInS sweep(sweep_S);
  SweptProbeBoxMemo probe_box(pair.X_SP, offset_S, sweep);
  DescendBvhPair<kOrder>(
      pair.P.bvh(), pair.S.bvh(),
      [&](const BvhNode& a, const BvhNode& b, double* key) {
        double hi;
        return SweptBoxContactInterval(probe_box(a), b, sweep, s_best, key, &hi);
      },
      [&](double lo) { return lo <= s_best; },
      [&](int ip, int is) {
        return ForEachTrianglePair(pair.P.bvh(), pair.S.bvh(), ip, is, [&](int tp, int ts) {
          const double t = TrianglePairContact(pair, tp, ts, offset_S, sweep_S);
          if (t <= s_best) s_best = t, hit = true;
          return true;
        });
      },
      counters);
  return hit ? s_best : -1.0;
}

// A colliding pose of the probe against the scene (random orientation,
// centre 0.1-0.6 scene radii from the scene's).
Isometry3 CollidingPose(const Model& P, const Model& S, std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> frac(0.1, 0.6);
  for (;;) {
    Isometry3 X = Isometry3::Identity();
    X.linear() = Quaternion(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    const Vector3 u = Vector3(g(rng), g(rng), g(rng)).normalized();
    X.translation() = S->center() + frac(rng) * S->radius() * u - X.linear() * P->center();
    if (InCollision(ModelPair(*P, *S, X, Isometry3::Identity()), Vector3::Zero())) return X;
  }
}

// The real meshes these tests sweep (CGAL's, from scripts/fetch_meshes.sh),
// centred and scaled to a 0.1 m bounding sphere, loaded once per test.
class TranslationalCcd : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* name : {"cow", "knot1", "camel"})
      PD_REQUIRE_FILE(kMeshDir + "/" + name + ".off", "run scripts/fetch_meshes.sh");
    cow_ = test::LoadCentredModel(kMeshDir + "/cow.off");
    knot1_ = test::LoadCentredModel(kMeshDir + "/knot1.off");
    camel_ = test::LoadCentredModel(kMeshDir + "/camel.off");
  }
  Model cow_, knot1_, camel_;
};

TEST_F(TranslationalCcd, FirstContactEqualsBruteForceOverAllTrianglePairsOnRealMeshes) {
  const Model P = cow_, S = knot1_;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  int contacts = 0, sweeps = 0;
  for (int k = 0; k < 4; ++k) {
    const ModelPair pair(*P, *S, CollidingPose(P, S, rng), Isometry3::Identity());
    std::vector<SupportPlaneStart> starts;
    ComputeSupportPlaneStarts(pair, 48, &starts);
    // Out-projections as PolyDepth makes them: a free support-plane start
    // toward the query; and a short sweep from there in a random direction
    // (mostly free).
    for (int i : {0, 5}) {
      const Vector3 from = starts[i].q_S;
      ASSERT_FALSE(InCollision(pair, from));
      const Vector3 u = Vector3(g(rng), g(rng), g(rng)).normalized();
      for (const Vector3& sweep : {Vector3(-from), Vector3(0.05 * from.norm() * u)}) {
        const double s = FirstContactAlongTranslation(pair, from, sweep);
        const double brute = BruteForceFirstContact(pair, from, sweep);
        ++sweeps;
        if (brute < 0) {
          EXPECT_LT(s, 0) << "pose " << k << " start " << i << ": CCD found a contact brute force did not";
          continue;
        }
        ++contacts;
        EXPECT_NEAR(s, brute, 1e-12) << "pose " << k << " start " << i;
      }
    }
  }
  EXPECT_EQ(sweeps, 16);
  EXPECT_GE(contacts, 8);  // every start-to-query sweep touches
}

// Sweeps leaving a touching configuration (PolyDepth's out-projection after
// an in-projection): most triangle pairs of the leaf pairs there lie near
// each other's planes, where the CCD's plane prefilter (a pair whose
// triangles stay on one side of each other's plane over the sweep is
// skipped) must keep every pair that touches. Short to long sweeps, in
// random directions and toward / along the contact.
TEST_F(TranslationalCcd, FirstContactFromTouchingConfigurationsEqualsBruteForce) {
  const Model P = knot1_, S = cow_;
  std::mt19937_64 rng(13);
  std::normal_distribution<double> g;
  int sweeps = 0, contacts = 0, near_start = 0;
  for (int k = 0; k < 3; ++k) {
    const ModelPair pair(*P, *S, CollidingPose(P, S, rng), Isometry3::Identity());
    std::vector<SupportPlaneStart> starts;
    ComputeSupportPlaneStarts(pair, 48, &starts);
    for (int i : {0, 3}) {
      const Vector3 from = starts[i].q_S;
      const double s = FirstContactAlongTranslation(pair, from, -from);
      ASSERT_GT(s, 0.0);
      // Backed off by PolyDepth's margin (1e-8 of the size).
      const Vector3 q_c = from - (s - 1e-8 * pair.size() / from.norm()) * from;
      ASSERT_FALSE(InCollision(pair, q_c));
      const Vector3 toward = -from.normalized();
      for (double len : {1e-4, 1e-3, 1e-2, 1e-1}) {
        const Vector3 u = Vector3(g(rng), g(rng), g(rng)).normalized();
        const Vector3 along = (u - u.dot(toward) * toward).normalized();
        for (const Vector3& dir : {u, toward, along, Vector3((along + 0.01 * toward).normalized())}) {
          const Vector3 sweep = len * pair.size() * dir;
          const double ccd = FirstContactAlongTranslation(pair, q_c, sweep);
          const double brute = BruteForceFirstContact(pair, q_c, sweep);
          ++sweeps;
          if (brute < 0) {
            EXPECT_LT(ccd, 0) << "pose " << k << " start " << i << " len " << len;
            continue;
          }
          ++contacts;
          if (brute * len < 1e-3) ++near_start;
          EXPECT_NEAR(ccd, brute, 1e-12) << "pose " << k << " start " << i << " len " << len;
        }
      }
    }
  }
  EXPECT_EQ(sweeps, 96);
  EXPECT_GE(contacts, 30) << sweeps;     // many touch
  EXPECT_GE(near_start, 10) << contacts;  // some within 1e-3 of the size of the start
}

// The early stop for callers that need the first contact only at or after
// s_stop (PolyDepth ranking its cold starts): a first contact at or after
// s_stop is found exactly; one before it is reported as some contact before
// s_stop, never earlier than the first (brute force over all triangle pairs).
TEST_F(TranslationalCcd, EarlyStopBeforeSStopReportsAContactAndIsExactAfterIt) {
  const Model P = cow_, S = knot1_;
  std::mt19937_64 rng(17);
  int exact = 0, early = 0;
  for (int k = 0; k < 3; ++k) {
    const ModelPair pair(*P, *S, CollidingPose(P, S, rng), Isometry3::Identity());
    std::vector<SupportPlaneStart> starts;
    ComputeSupportPlaneStarts(pair, 48, &starts);
    for (int i : {0, 2, 4}) {
      const Vector3 from = starts[i].q_S;
      const double brute = BruteForceFirstContact(pair, from, -from);
      ASSERT_GT(brute, 0.0) << "pose " << k << " start " << i;
      for (double f : {0.5, 0.999, 1.001, 2.0}) {
        const double s_stop = f * brute;
        const double s = FirstContactAlongTranslation(pair, from, -from, s_stop);
        if (brute >= s_stop) {
          ++exact;
          EXPECT_NEAR(s, brute, 1e-12) << "pose " << k << " start " << i << " f " << f;
        } else {
          ++early;
          EXPECT_GE(s, brute - 1e-12) << "pose " << k << " start " << i << " f " << f;
          EXPECT_LT(s, s_stop) << "pose " << k << " start " << i << " f " << f;
        }
      }
    }
  }
  EXPECT_EQ(exact, 18);
  EXPECT_EQ(early, 18);
}

// Short sweeps near the contact, after the probe moved and turned since a
// list was built there (of leaf pairs or twig pairs): the CCD walks the list (skipping entries
// their separating axis keeps apart) and finds the first contact brute force
// over all triangle pairs finds.
// Bounded time: a CCD stopped by the caller (ModelPair::stop_ccd) returns a
// fraction no later than the exact first contact (brute force), says it
// stopped, and the probe there is collision-free; one not stopped is exact.
TEST_F(TranslationalCcd, AStoppedSearchReturnsAFreePointNoLaterThanTheFirstContact) {
  const Model P = cow_, S = knot1_;
  std::mt19937_64 rng(11);
  int stopped_short = 0, checked = 0;
  for (int k = 0; k < 2; ++k) {
    ModelPair pair(*P, *S, CollidingPose(P, S, rng), Isometry3::Identity());
    std::vector<SupportPlaneStart> starts;
    ComputeSupportPlaneStarts(pair, 48, &starts);
    for (size_t i = 0; i < std::min<size_t>(starts.size(), 4); ++i) {
      const Vector3 from = starts[i].q_S, sweep = -starts[i].q_S;
      const double exact = BruteForceFirstContact(pair, from, sweep);
      ASSERT_GE(exact, 0.0);  // the query pose collides: the sweep to it touches
      for (int stop_after : {0, 3, 30, 300}) {
        int asked = 0;
        const std::function<bool()> stop = [&] { return ++asked > stop_after; };
        pair.stop_ccd = &stop;
        bool stopped = false;
        const double s = FirstContactAlongTranslation(pair, from, sweep, -1.0, nullptr, nullptr, &stopped);
        pair.stop_ccd = nullptr;
        ++checked;
        if (!stopped) {
          EXPECT_NEAR(s, exact, 1e-12) << k << " " << i << " " << stop_after;
          continue;
        }
        ASSERT_GE(s, 0.0);
        EXPECT_LE(s, exact + 1e-12) << k << " " << i << " " << stop_after;
        // Free there (a hair before s, against round-off at a touching s).
        EXPECT_FALSE(InCollision(pair, from + std::max(0.0, s - 1e-9) * sweep)) << k << " " << i;
        stopped_short += s < exact - 1e-9;
      }
    }
  }
  EXPECT_GE(checked, 24);
  EXPECT_GT(stopped_short, 5);  // the stop did stop searches short of the contact
}

// The stop is asked between the parts of a candidate-list walk too (the
// walk of a dense list's prefix costs thousands of tests): a search stopped
// there returns where the parts walked showed the sweep free.
TEST_F(TranslationalCcd, AStoppedListWalkReturnsTheFreePartItWalked) {
  const Model P = cow_, S = knot1_;
  std::mt19937_64 rng(9);
  int stopped_in_list = 0;
  for (int k = 0; k < 3; ++k) {
    ModelPair pair(*P, *S, CollidingPose(P, S, rng), Isometry3::Identity());
    std::vector<SupportPlaneStart> starts;
    ComputeSupportPlaneStarts(pair, 48, &starts);
    const Vector3 from = starts[0].q_S;
    CandidatePairs list;
    list.Build(pair, from, 0.03 * pair.size(), CandidatePairs::Grain::kLeafPairs);
    const double covered = list.CoveredFraction(pair, from, -from, 0.0);
    ASSERT_GT(covered, 0.0);
    const double exact = BruteForceFirstContact(pair, from, -from);
    ASSERT_GT(exact, covered);  // past the list: its walk finds nothing
    pair.candidates = &list;
    const std::function<bool()> stop = [] { return true; };
    pair.stop_ccd = &stop;
    bool stopped = false;
    const double s = FirstContactAlongTranslation(pair, from, -from, -1.0, nullptr, nullptr, &stopped);
    pair.stop_ccd = nullptr;
    pair.candidates = nullptr;
    EXPECT_TRUE(stopped) << "pose " << k;
    EXPECT_GT(s, 0.0) << "pose " << k;  // the first part, walked before the stop
    EXPECT_LT(s, covered) << "pose " << k;
    EXPECT_FALSE(InCollision(pair, from - s * from)) << "pose " << k;
    stopped_in_list += stopped && s > 0.0 && s < covered;
  }
  EXPECT_EQ(stopped_in_list, 3);
}

// A work budget (the stop reading the pair's counters, as PolyDepth's
// max_work does) stops each path of the search within a few tests of it:
// the descent from the roots, the descent from the last sweep's cut and a
// candidate list's walk count their box tests before each time they ask
// (they counted them only when done: a bounded query ran 1.6k tests past
// its budget in one CCD). The point returned is free and no later than the
// first contact.
TEST_F(TranslationalCcd, AWorkBudgetStopsEachPathOfTheSearchWithinAFewTestsOfIt) {
  const Model P = knot1_, S = cow_;
  std::mt19937_64 rng(31);
  std::normal_distribution<double> g;
  // A pop expands one pair (2 box tests) or a leaf pair (up to 4 triangle
  // tests); a descent from a cut tests the cut's pairs first, asking every
  // 64; a list walk asks every 16 entries (a box test and up to 4 triangle
  // tests each).
  constexpr int64_t kDescentSlack = 4, kCutSlack = 64 + 4, kListSlack = 16 * 5;
  enum Path { kRoots, kCut, kList };
  int checked[3] = {0, 0, 0};
  for (int k = 0; k < 12; ++k) {
    const ModelPair plain(*P, *S, CollidingPose(P, S, rng), Isometry3::Identity());
    std::vector<SupportPlaneStart> starts;
    ComputeSupportPlaneStarts(plain, 48, &starts);
    // From the contact (a start landed, a hair back) along it, as a
    // search's sweeps go: the pairs touching at the start cost most.
    const double landed = FirstContactAlongTranslation(plain, starts[0].q_S, -starts[0].q_S);
    ASSERT_GT(landed, 0.0);
    const Vector3 from =
        (1.0 - landed) * starts[0].q_S + 1e-8 * plain.size() * starts[0].q_S.normalized();
    const Vector3 in = -from.normalized();
    auto along_contact = [&](double into) {
      const Vector3 u = Vector3(g(rng), g(rng), g(rng)).normalized();
      return Vector3(0.05 * plain.size() * ((u - u.dot(in) * in).normalized() + into * in));
    };
    const Vector3 sweep = along_contact(0.2);
    // Cut: the last sweep (here `sweep`) ended near; the next goes on from
    // where it landed, another way.
    const double s_first = FirstContactAlongTranslation(plain, from, sweep);
    const Vector3 landing =
        from + (s_first < 0 ? 1.0 : std::max(0.0, s_first - 1e-8 * plain.size() / sweep.norm())) *
                   sweep;
    const Vector3 next = along_contact(0.0);
    // List: a sweep from a little off the contact along it, through a list
    // built a way back (the probe has moved across it since), so that its
    // walk's prefix holds every entry within that motion (a dense list).
    const Vector3 off = from - 2e-3 * plain.size() * in;
    const Vector3 across = along_contact(0.0);
    CandidatePairs list;
    list.Build(plain, off - 0.3 * across, 0.12 * plain.size(), CandidatePairs::Grain::kLeafPairs);
    for (Path path : {kRoots, kCut, kList}) {
      const Vector3 start = path == kCut ? landing : path == kList ? off : from;
      const Vector3 d = path == kRoots ? sweep : path == kCut ? next : across;
      if (path == kList && !(list.CoveredFraction(plain, start, d, 0.0) > 0.0)) continue;
      // The same search unstopped (its work sets the budget) and stopped.
      auto search = [&](ProximityCounters* counters, const std::function<bool()>* stop,
                        bool* stopped) {
        ModelPair pair = plain;
        DescentFront front;
        if (path == kCut) {
          pair.front = &front;
          FirstContactAlongTranslation(pair, from, sweep);  // leaves its cut
        }
        if (path == kList) pair.candidates = &list;
        pair.counters = counters;
        pair.stop_ccd = stop;
        return FirstContactAlongTranslation(pair, start, d, -1.0, nullptr, nullptr, stopped);
      };
      ProximityCounters full;
      const double exact = search(&full, nullptr, nullptr);
      const int64_t slack = path == kList ? kListSlack : path == kCut ? kCutSlack : kDescentSlack;
      const int64_t limit = full.total() / 2;
      if (limit < 2 * slack) continue;  // too short a search to stop within it
      ProximityCounters counters;
      const std::function<bool()> stop = [&] { return counters.total() >= limit; };
      bool stopped = false;
      const double s = search(&counters, &stop, &stopped);
      EXPECT_TRUE(stopped) << "pose " << k << " path " << path;
      EXPECT_LE(counters.total(), limit + slack)
          << "pose " << k << " path " << path << " limit " << limit;
      EXPECT_GE(s, 0.0);
      if (exact >= 0.0) EXPECT_LE(s, exact + 1e-12) << "pose " << k << " path " << path;
      EXPECT_FALSE(InCollision(plain, start + std::max(0.0, s - 1e-9) * d))
          << "pose " << k << " path " << path;
      ++checked[path];
    }
  }
  // Each path was stopped in several searches long enough to stop in.
  EXPECT_GE(checked[kRoots], 4);
  EXPECT_GE(checked[kCut], 4);
  EXPECT_GE(checked[kList], 4);
  RecordProperty("checked", std::to_string(checked[0]) + " " + std::to_string(checked[1]) + " " +
                                std::to_string(checked[2]));
}

TEST_F(TranslationalCcd, FirstContactThroughACandidateListEqualsBruteForceAfterMotion) {
  const Model P = cow_, S = knot1_;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g;
  int listed = 0, contacts = 0, partly = 0;
  for (int k = 0; k < 4; ++k) {
    const Isometry3 X_WP = CollidingPose(P, S, rng);
    const ModelPair pair(*P, *S, X_WP, Isometry3::Identity());
    std::vector<SupportPlaneStart> starts;
    ComputeSupportPlaneStarts(pair, 48, &starts);
    // A configuration just off the contact: a start out-projected to it.
    const Vector3 from = starts[0].q_S;
    const double s = FirstContactAlongTranslation(pair, from, -from);
    ASSERT_GT(s, 0.0);
    const Vector3 q_c = from - (s - 1e-3) * from;
    const double radius = 0.03 * pair.size();
    CandidatePairs list;
    // Both grains (candidate_pairs.h), alternating.
    list.Build(pair, q_c, radius,
               k % 2 ? CandidatePairs::Grain::kTwigPairs : CandidatePairs::Grain::kLeafPairs);
    // The probe moves and turns a little (its points by a few percent of
    // the radius), then sweeps from near q_c in random directions.
    Isometry3 X_WP2 = X_WP;
    X_WP2.linear() = X_WP.linear() * Eigen::AngleAxisd(0.004, Vector3(g(rng), g(rng), g(rng)).normalized()).toRotationMatrix();
    X_WP2.translation() += 0.1 * radius * Vector3(g(rng), g(rng), g(rng)).normalized();
    ModelPair moved(*P, *S, X_WP2, Isometry3::Identity());
    moved.candidates = &list;
    ModelPair plain(*P, *S, X_WP2, Isometry3::Identity());
    for (int i = 0; i < 12; ++i) {
      const Vector3 start = q_c + 0.2 * radius * Vector3(g(rng), g(rng), g(rng)).normalized();
      if (InCollision(plain, start)) continue;
      // Every third sweep is long enough to leave the list.
      const double length = i % 3 == 2 ? 1.5 : 0.3;
      const Vector3 sweep = length * radius * Vector3(g(rng), g(rng), g(rng)).normalized() +
                            (i % 2 ? Vector3(0.3 * radius * (q_c - start).normalized()) : Vector3::Zero());
      const double covered = list.CoveredFraction(moved, start, sweep, 0.0);
      if (covered <= 0.0) continue;
      ++listed;
      partly += covered < 1.0;
      const double brute = BruteForceFirstContact(plain, start, sweep);
      const double ccd = FirstContactAlongTranslation(moved, start, sweep);
      if (brute < 0) {
        EXPECT_LT(ccd, 0) << "pose " << k << " sweep " << i;
        continue;
      }
      ++contacts;
      EXPECT_NEAR(ccd, brute, 1e-12) << "pose " << k << " sweep " << i;
    }
  }
  EXPECT_GE(listed, 16) << contacts;  // the list, not the descent, answered these
  EXPECT_GE(contacts, 4) << listed;   // and some of them touch
  // Some sweeps leave the list: past the part it shows contact-free the
  // descent looks for the contact (translational_ccd.cc, s_min).
  EXPECT_GE(partly, 4) << listed;
}

// A sweep that starts inside a list and leaves it before its first contact:
// the list shows its first part contact-free and the descent looks past it
// only; the contact is the one brute force finds.
TEST_F(TranslationalCcd, FirstContactPastTheListEqualsBruteForce) {
  const Model P = cow_, S = knot1_;
  std::mt19937_64 rng(9);
  int past = 0;
  for (int k = 0; k < 4; ++k) {
    const Isometry3 X_WP = CollidingPose(P, S, rng);
    ModelPair pair(*P, *S, X_WP, Isometry3::Identity());
    std::vector<SupportPlaneStart> starts;
    ComputeSupportPlaneStarts(pair, 48, &starts);
    for (int i = 0; i < 2; ++i) {
      // From a free support-plane start toward the query, with the list
      // built around the start.
      const Vector3 from = starts[i].q_S;
      CandidatePairs list;
      list.Build(pair, from, 0.03 * pair.size(),
                 i % 2 ? CandidatePairs::Grain::kTwigPairs : CandidatePairs::Grain::kLeafPairs);
      const double covered = list.CoveredFraction(pair, from, -from, 0.0);
      ASSERT_GT(covered, 0.0);
      ASSERT_LT(covered, 1.0);
      const double brute = BruteForceFirstContact(pair, from, -from);
      ASSERT_GT(brute, covered);
      pair.candidates = &list;
      EXPECT_NEAR(FirstContactAlongTranslation(pair, from, -from), brute, 1e-12)
          << "pose " << k << " start " << i;
      LeafPairRecord record;
      record.distance = 1e-4 * pair.size();
      bool complete = false;
      EXPECT_NEAR(FirstContactAlongTranslation(pair, from, -from, -1.0, &record, &complete), brute,
                  1e-12);
      EXPECT_TRUE(complete);
      pair.candidates = nullptr;
      ++past;
    }
  }
  EXPECT_EQ(past, 8);
}

TEST_F(TranslationalCcd, BestFirstDescentFindsTheSameContactWithFewerBoxTestsOnLongSweeps) {
  const Model P = knot1_, S = camel_;
  std::mt19937_64 rng(11);
  ProximityCounters depth_first, best_first;
  int sweeps = 0;
  for (int k = 0; k < 6; ++k) {
    const ModelPair pair(*P, *S, CollidingPose(P, S, rng), Isometry3::Identity());
    std::vector<SupportPlaneStart> starts;
    ComputeSupportPlaneStarts(pair, 48, &starts);
    for (int i = 0; i < 8; ++i) {
      // Long sweeps: from a maximally clear start all the way to the query.
      const Vector3 from = starts[i].q_S, sweep = -from;
      const double s_df = DescentFirstContact<DescentOrder::kDepthFirst>(pair, from, sweep,
                                                                         &depth_first);
      const double s_bf = DescentFirstContact<DescentOrder::kBestFirst>(pair, from, sweep,
                                                                        &best_first);
      EXPECT_EQ(s_df, s_bf) << "pose " << k << " start " << i;
      EXPECT_GT(s_bf, 0.0);
      // The library's CCD is the best-first descent.
      EXPECT_NEAR(FirstContactAlongTranslation(pair, from, sweep), s_bf, 1e-12);
      ++sweeps;
    }
  }
  ASSERT_EQ(sweeps, 48);
  // Measured: 0.62 of depth-first's box tests (45.9k vs 74.3k).
  EXPECT_LT(best_first.box_tests, 0.8 * depth_first.box_tests)
      << "best-first " << best_first.box_tests << " vs depth-first " << depth_first.box_tests;
}

// A search's next sweep starts where the last one landed (PolyDepth's
// iterations): its descent starts at the last one's cut (descent_front.h)
// and finds the same first contact as brute force, with fewer box tests
// than a descent from the roots. A sweep from elsewhere starts at the roots.
TEST_F(TranslationalCcd, ASweepFromTheLastLandingStartsAtItsCutAndFindsTheSameContact) {
  const Model P = knot1_, S = cow_;
  std::mt19937_64 rng(23);
  std::normal_distribution<double> g;
  int64_t with_cut = 0, from_roots = 0;
  int sweeps = 0, contacts = 0;
  for (int k = 0; k < 3; ++k) {
    const Isometry3 X = CollidingPose(P, S, rng);
    ModelPair pair(*P, *S, X, Isometry3::Identity());
    DescentFront front;
    ProximityCounters counters;
    pair.front = &front;
    pair.counters = &counters;
    const ModelPair plain(*P, *S, X, Isometry3::Identity());
    std::vector<SupportPlaneStart> starts;
    ComputeSupportPlaneStarts(plain, 48, &starts);
    Vector3 q = starts[0].q_S;
    Vector3 sweep = -q;
    for (int step = 0; step < 8; ++step) {
      ProximityCounters plain_counters;
      ModelPair counted = plain;
      counted.counters = &plain_counters;
      const int64_t before = counters.box_tests;
      const double s = FirstContactAlongTranslation(pair, q, sweep);
      const double s_roots = FirstContactAlongTranslation(counted, q, sweep);
      const double brute = BruteForceFirstContact(plain, q, sweep);
      EXPECT_NEAR(s, brute, 1e-12) << "pose " << k << " step " << step;
      EXPECT_EQ(s, s_roots) << "pose " << k << " step " << step;
      if (step > 0) {  // the first starts at the roots: no cut yet
        with_cut += counters.box_tests - before;
        from_roots += plain_counters.box_tests;
      }
      ++sweeps;
      // Land a margin back from the contact (or at the end), then sweep
      // 0.1-1% of the size along the contact, a little into it.
      const double t = s < 0 ? 1.0 : std::max(0.0, s - 1e-8 * plain.size() / sweep.norm());
      contacts += s >= 0;
      q += t * sweep;
      const Vector3 in = -q.normalized();
      const Vector3 u = Vector3(g(rng), g(rng), g(rng)).normalized();
      const Vector3 along = (u - u.dot(in) * in).normalized();
      sweep = (0.001 + 0.009 * (step % 3) / 2.0) * plain.size() * (along + 0.2 * in).normalized();
    }
    // A sweep from elsewhere: the descent from the roots, test for test.
    ProximityCounters far_cut, far_roots;
    pair.counters = &far_cut;
    ModelPair counted = plain;
    counted.counters = &far_roots;
    const Vector3 from = starts[3].q_S;
    EXPECT_EQ(FirstContactAlongTranslation(pair, from, -from),
              FirstContactAlongTranslation(counted, from, -from));
    EXPECT_EQ(far_cut.box_tests, far_roots.box_tests) << "pose " << k;
  }
  EXPECT_EQ(sweeps, 24);
  EXPECT_GE(contacts, 12);
  // Measured: 0.55 of the box tests from the roots (7.7k vs 14.0k).
  EXPECT_LT(with_cut, 0.8 * from_roots) << with_cut << " vs " << from_roots;
}

// A CCD that records (PolyDepth's out-projection before it localises at the
// landing point): the same first contact, and the record holds the leaf
// pair of every triangle pair within the record's distance at the landing
// point (brute force over all triangle pairs), so the localisation there
// from the record finds exactly the constraints a full descent finds, with
// fewer box tests.
TEST_F(TranslationalCcd, RecordHoldsEveryLeafPairNearTheLandingPointAndLocalisesTheSame) {
  const Model P = knot1_, S = cow_;
  std::mt19937_64 rng(17);
  const std::vector<int> leaf_P = test::LeafOfTriangle(P->bvh(), P->mesh().num_triangles());
  const std::vector<int> leaf_S = test::LeafOfTriangle(S->bvh(), S->mesh().num_triangles());
  int near_pairs = 0, localisations = 0;
  ProximityCounters with_record, by_descent;
  for (int k = 0; k < 3; ++k) {
    ModelPair pair(*P, *S, CollidingPose(P, S, rng), Isometry3::Identity());
    std::vector<SupportPlaneStart> starts;
    ComputeSupportPlaneStarts(pair, 48, &starts);
    for (int i : {0, 2, 5}) {
      const Vector3 from = starts[i].q_S;
      LeafPairRecord record;
      // PolyDepth's default contact distance, and 30 times it: pairs that
      // near but do not touch by the first contact are recorded too.
      record.distance = (i == 2 ? 3e-3 : 1e-4) * pair.size();
      bool complete = false;
      const double s = FirstContactAlongTranslation(pair, from, -from, -1.0, &record, &complete);
      ASSERT_TRUE(complete);
      ASSERT_GT(s, 0.0);
      EXPECT_EQ(s, FirstContactAlongTranslation(pair, from, -from)) << "pose " << k;
      const Vector3 q_c = from - (s - 1e-8 * pair.size() / from.norm()) * from;
      ASSERT_FALSE(InCollision(pair, q_c));
      // Every triangle pair within the distance at q_c: its leaf pair is recorded.
      const double d = record.distance;
      std::vector<std::pair<int, int>> recorded;
      for (const auto& e : record.pairs) recorded.push_back({e.ip, e.is});
      std::sort(recorded.begin(), recorded.end());
      test::ForEachTrianglePairWithin(pair, q_c, d, [&](int tp, int ts) {
        ++near_pairs;
        EXPECT_TRUE(std::binary_search(recorded.begin(), recorded.end(),
                                       std::make_pair(leaf_P[tp], leaf_S[ts])))
            << "pose " << k << " start " << i << " triangles " << tp << ", " << ts;
      });
      // The localisation at q_c, by descent and from the record.
      std::vector<ContactConstraint> by_tree, by_record;
      pair.counters = &by_descent;
      CollectContactConstraints(pair, q_c, d, &by_tree);
      record.q_S = q_c;
      record.valid = true;
      pair.recorded = &record;
      pair.counters = &with_record;
      CollectContactConstraints(pair, q_c, d, &by_record);
      pair.recorded = nullptr;
      pair.counters = nullptr;
      auto key = [](const ContactConstraint& c) {
        return std::make_tuple(static_cast<int>(c.kind), c.feature_P, c.feature_S);
      };
      auto order = [&](std::vector<ContactConstraint>& cs) {
        std::sort(cs.begin(), cs.end(), [&](const ContactConstraint& a, const ContactConstraint& b) {
          return key(a) < key(b);
        });
      };
      order(by_tree);
      order(by_record);
      ASSERT_EQ(by_tree.size(), by_record.size()) << "pose " << k << " start " << i;
      EXPECT_FALSE(by_tree.empty());
      for (size_t j = 0; j < by_tree.size(); ++j) {
        EXPECT_EQ(key(by_tree[j]), key(by_record[j]));
        EXPECT_EQ(by_tree[j].n_S, by_record[j].n_S);
        EXPECT_EQ(by_tree[j].c, by_record[j].c);
      }
      ++localisations;
    }
  }
  EXPECT_EQ(localisations, 9);
  EXPECT_GE(near_pairs, 9);
  EXPECT_LT(with_record.box_tests, by_descent.box_tests / 2)
      << with_record.box_tests << " vs " << by_descent.box_tests;
}

}  // namespace
}  // namespace pd
