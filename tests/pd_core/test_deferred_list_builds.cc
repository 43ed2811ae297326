// PolyDepthOptions::defer_list_builds: warm queries answer without
// rebuilding their candidate list and leave the rebuild to
// PolyDepthSolver::PrepareNext (the geometry thread's idle time). Along a
// slide of a real mesh tool over a real mesh object (bench_pd's
// fandisk_elephant pair), the deferring solver must give the answers the
// default solver gives, with no list build inside any Solve, its lists
// rebuilt by PrepareNext instead, in pieces as small as its caller asks.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "pd_core/polydepth/polydepth.h"
#include "tests/pd_core/pair_pd_test_helpers.h"
#include "tests/pd_core/fandisk_on_elephant.h"

namespace pd {
namespace {

using test::Pose;

class DeferredListBuilds : public test::FandiskOnElephant {
 protected:
  void SetUp() override {
    FandiskOnElephant::SetUp();
    // From pose 1200, 1 ms apart: sliding 0.1 m/s along x and turning 20 deg/s.
    for (int i = 0; i < kPoses; ++i) {
      const Quaternion q_i(Eigen::AngleAxisd(0.35 * 1e-3 * i, Vector3::UnitZ()) *
                           Pose1200Rotation());
      path.push_back(Pose(Pose1200Position() + Vector3(1e-4 * i, 0, 0), q_i));
    }
  }
  static constexpr int kPoses = 240;
  std::vector<Isometry3> path;
};

TEST_F(DeferredListBuilds, SameAnswersWithTheRebuildsOutOfTheQueries) {
  PolyDepthOptions deferring;
  deferring.defer_list_builds = true;
  PolyDepthSolver usual(tool, object), deferred(tool, object, deferring),
      never_prepared(tool, object, deferring);
  int usual_builds = 0, prepared_lists = 0, colliding = 0, never_prepared_builds = 0;
  int64_t deferred_work = 0, never_prepared_work = 0;
  for (int i = 0; i < kPoses; ++i) {
    const PenetrationResult a = usual.Solve(path[i], Isometry3::Identity(), true);
    const PenetrationResult b = deferred.Solve(path[i], Isometry3::Identity(), true);
    const PenetrationResult c = never_prepared.Solve(path[i], Isometry3::Identity(), true);
    prepared_lists += deferred.PrepareNext().lists_completed;
    usual_builds += a.list_builds;
    colliding += a.in_collision;
    // No list is built while a deferring solver answers.
    EXPECT_EQ(b.list_builds, 0) << "pose " << i;
    EXPECT_EQ(b.work.list_builds, 0) << "pose " << i;
    never_prepared_builds += c.list_builds;
    deferred_work += b.box_tests + b.triangle_tests;
    never_prepared_work += c.box_tests + c.triangle_tests;
    // The lists only speed the search: the same answers (to round-off).
    for (const PenetrationResult* r : {&b, &c}) {
      ASSERT_EQ(r->in_collision, a.in_collision) << "pose " << i;
      ASSERT_EQ(r->valid, a.valid) << "pose " << i;
      EXPECT_NEAR(r->depth, a.depth, 1e-12 * (1.0 + a.depth) + 1e-12) << "pose " << i;
      EXPECT_LE((r->translation_W - a.translation_W).norm(), 1e-12) << "pose " << i;
    }
  }
  // The path is a real slide: mostly in contact, and the usual solver
  // rebuilt its list along it.
  EXPECT_GT(colliding, kPoses / 2);
  EXPECT_GT(usual_builds, 5);
  // The deferring solver's lists came from PrepareNext, and they pay: the
  // same solver never prepared builds each list in the query after the one
  // that asked for it (AQueryThatNeedsThePausedBuildCompletesIt) and
  // answers the query between without it, for the same answers.
  EXPECT_GT(prepared_lists, 5);
  EXPECT_GT(never_prepared_builds, 5);
  EXPECT_LT(deferred_work, never_prepared_work);
}

TEST_F(DeferredListBuilds, PrepareNextStopsWhenAskedAndGoesOnLater) {
  PolyDepthOptions deferring;
  deferring.defer_list_builds = true;
  PolyDepthSolver usual(tool, object), deferred(tool, object, deferring);
  int builds_in_pieces = 0;
  for (int i = 0; i < kPoses; ++i) {
    const PenetrationResult a = usual.Solve(path[i], Isometry3::Identity(), true);
    const PenetrationResult b = deferred.Solve(path[i], Isometry3::Identity(), true);
    ASSERT_EQ(b.in_collision, a.in_collision) << "pose " << i;
    EXPECT_NEAR(b.depth, a.depth, 1e-12 * (1.0 + a.depth) + 1e-12) << "pose " << i;
    // A caller that always asks to stop: each call does a few dozen
    // pairs' work, and the build completes after many calls.
    int calls = 0, lists = 0;
    for (;;) {
      const PolyDepthSolver::Preparation p = deferred.PrepareNext([] { return true; });
      ++calls;
      EXPECT_LE(p.box_tests, 200) << "pose " << i;
      lists += p.lists_completed;
      if (p.done) break;
      EXPECT_EQ(p.lists_completed, 0);
      ASSERT_LT(calls, 100000);
    }
    if (calls > 10) {
      ++builds_in_pieces;
      EXPECT_EQ(lists, 1) << "pose " << i;
    }
  }
  EXPECT_GT(builds_in_pieces, 5);
  // With nothing pending a call does nothing.
  const PolyDepthSolver::Preparation idle = deferred.PrepareNext([] { return true; });
  EXPECT_TRUE(idle.done);
  EXPECT_EQ(idle.box_tests, 0);
  EXPECT_EQ(idle.lists_completed, 0);
}

// When the idle time did not suffice (the build still paused) and the next
// query needs that list, the query completes it before going on rather
// than answering without a list (which left the next idle time short again:
// a cascade of slow queries on the benchmark's cow_armadillo path).
TEST_F(DeferredListBuilds, AQueryThatNeedsThePausedBuildCompletesIt) {
  PolyDepthOptions deferring;
  deferring.defer_list_builds = true;
  PolyDepthSolver deferred(tool, object, deferring), usual(tool, object);
  int finished_in_query = 0, paused = 0;
  for (int i = 0; i < kPoses; ++i) {
    const PenetrationResult a = usual.Solve(path[i], Isometry3::Identity(), true);
    const PenetrationResult b = deferred.Solve(path[i], Isometry3::Identity(), true);
    EXPECT_NEAR(b.depth, a.depth, 1e-12 * (1.0 + a.depth) + 1e-12) << "pose " << i;
    if (b.list_builds > 0) {
      ++finished_in_query;
      EXPECT_GT(b.work.list_builds, 0) << "pose " << i;  // booked to this query
    }
    // No idle time at all: one call, a few dozen pairs.
    paused += !deferred.PrepareNext([] { return true; }).done;
  }
  EXPECT_GT(paused, 5);
  EXPECT_GT(finished_in_query, 2);
}

TEST_F(DeferredListBuilds, ResetWarmStartDropsTheBuildUnderWay) {
  PolyDepthOptions deferring;
  deferring.defer_list_builds = true;
  PolyDepthSolver deferred(tool, object, deferring);
  bool pending = false;
  for (int i = 0; i < kPoses && !pending; ++i) {
    deferred.Solve(path[i], Isometry3::Identity(), true);
    pending = !deferred.PrepareNext([] { return true; }).done;
  }
  ASSERT_TRUE(pending) << "no build was deferred along the path";
  deferred.ResetWarmStart();
  const PolyDepthSolver::Preparation p = deferred.PrepareNext();
  EXPECT_TRUE(p.done);
  EXPECT_EQ(p.box_tests, 0);
  EXPECT_EQ(p.lists_completed, 0);
}

}  // namespace
}  // namespace pd
