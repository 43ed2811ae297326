// A budget-stopped cold query leaves the rest of its search (the starts it
// cut, the shell, inner and deep probes) to the following coherent queries
// of the pair, which go on where it stopped (PolyDepthOptions::max_work,
// max_time_us; cold_probes.cc). Budgets here are work budgets (box plus
// triangle tests), so every run takes the same steps.
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <memory>
#include <vector>

#include "pd_core/geometry/make_shapes.h"
#include "pd_core/polydepth/cold_starts.h"
#include "pd_core/polydepth/polydepth.h"
#include "pd_core/proximity/model_pair.h"
#include "pd_core/reference/reference_pd.h"
#include "tests/pd_core/normalised_mesh.h"
#include "tests/prerequisites.h"

namespace pd {
namespace {

using Model = std::shared_ptr<const CollisionModel>;
const std::string kMeshDir = PD_TEST_MESH_DIR;

// bench_pd's random case 71 of dino_femur: the femur shallowly (1.1 mm)
// into a pocket of the dino that every landing from outside misses (they
// come in at 36 mm or more); only the cold query's inner and deep probes
// find it, and a budget of 20k tests stops the query long before them.
struct DinoFemurPocket {
  Model P = CollisionModel::Build(test::LoadNormalised("dino.off"));
  Model S = CollisionModel::Build(test::LoadNormalised("femur.off"));
  Isometry3 X_WS = Isometry3::Identity();
  Isometry3 X_WP = Isometry3::Identity();
  DinoFemurPocket() {
    X_WP.linear() = Quaternion(0.59485618837512522, -0.68024167485239018, -0.1323213781309911,
                               0.40731858763791756)
                        .normalized()
                        .toRotationMatrix();
    X_WP.translation() =
        Vector3(-0.031329725025528998, 0.04753868841604876, 0.018449275222514747);
  }
};
constexpr int64_t kWorkBudget = 20000;

// The probe held still after a cold query its budget cut: the following
// queries (same budget) reach the unbounded answer, each one free, build no
// leaf-pair list meanwhile, say they are going on with the cold search
// while they are, and stop saying so once it is complete; from then on
// (its list built) a query at the same pose costs next to nothing. Without the follow-up every query would keep the cut query's
// 41 mm answer (the probe pushed out through the far side of the dino).
TEST(ColdFollowUp, AHeldProbeGetsTheWholeColdSearchWithinAFewQueries) {
  PD_REQUIRE_FILE(kMeshDir + "/dino.off", "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(kMeshDir + "/femur.off", "run scripts/fetch_meshes.sh");
  const DinoFemurPocket c;
  ReferencePdOptions ro;
  ro.num_directions = 512;
  ro.refine_iterations = 64;
  const ReferencePdResult ref =
      ReferencePenetrationDepth(c.P->mesh(), c.X_WP, true, c.S->mesh(), c.X_WS, true, ro);
  ASSERT_TRUE(ref.in_collision);
  const double size = c.P->radius() + c.S->radius();
  PolyDepthOptions options;
  options.max_work = kWorkBudget;
  PolyDepthSolver solver(c.P, c.S, options);
  const PenetrationResult first = solver.Solve(c.X_WP, c.X_WS);
  ASSERT_TRUE(first.in_collision && first.valid);
  EXPECT_FALSE(first.converged);
  EXPECT_FALSE(first.cold_probes_resumed);
  // The case is what it is here for: the cut query misses the pocket.
  ASSERT_GT(first.depth, 5.0 * ref.depth) << "the budget no longer cuts this query short";
  int resumed = 0, reached_at = -1, done_at = -1;
  for (int k = 1; k <= 20; ++k) {
    const PenetrationResult r = solver.Solve(c.X_WP, c.X_WS, true);
    ASSERT_TRUE(r.in_collision && r.valid) << "query " << k;
    EXPECT_FALSE(ReferenceInCollision(c.P->mesh(), c.X_WP, true, c.S->mesh(), c.X_WS, true,
                                      r.translation_W * (1.0 + 2e-6 * size / r.depth)))
        << "query " << k << " answered a colliding translation";
    std::printf("[ query %2d ] depth %.6f resumed %d converged %d tests %lld\n", k, r.depth,
                r.cold_probes_resumed, r.converged,
                static_cast<long long>(r.box_tests + r.triangle_tests));
    if (reached_at < 0 && r.depth <= 1.10 * ref.depth) reached_at = k;
    if (done_at < 0) {
      if (r.cold_probes_resumed) ++resumed;
      // No leaf-pair list is built around an answer that may still move
      // to another basin (at a deep contact a build took most of a budget).
      EXPECT_EQ(r.list_builds, 0) << "query " << k;
      if (r.converged) done_at = k;
    } else {
      EXPECT_FALSE(r.cold_probes_resumed) << "query " << k << " after the search completed";
      // (The first query after it builds the list the others walk.)
      if (k > done_at + 1) EXPECT_LT(r.box_tests + r.triangle_tests, 1000) << "query " << k;
    }
  }
  std::printf("[ case     ] reference %.6f, first %.6f, within 10%% at query %d, done at %d\n",
              ref.depth, first.depth, reached_at, done_at);
  EXPECT_GE(reached_at, 1);
  EXPECT_LE(reached_at, 10);
  EXPECT_GE(done_at, 1);
  EXPECT_EQ(resumed, done_at) << "every query up to the last one went on with the search";
}

// What is left goes with the contact: a free query drops it (the next
// contact starts from the free frame, not from a cold search), and so does
// ResetWarmStart (the caller says the probe jumped).
TEST(ColdFollowUp, AFreeQueryOrAResetDropsWhatIsLeft) {
  PD_REQUIRE_FILE(kMeshDir + "/dino.off", "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(kMeshDir + "/femur.off", "run scripts/fetch_meshes.sh");
  const DinoFemurPocket c;
  PolyDepthOptions options;
  options.max_work = kWorkBudget;
  Isometry3 X_far = c.X_WP;
  X_far.translation() += Vector3(1.0, 0.0, 0.0);
  {
    PolyDepthSolver solver(c.P, c.S, options);
    ASSERT_FALSE(solver.Solve(c.X_WP, c.X_WS).converged);
    ASSERT_TRUE(solver.Solve(c.X_WP, c.X_WS, true).cold_probes_resumed);  // still going on
    ASSERT_FALSE(solver.Solve(X_far, c.X_WS, true).in_collision);
    EXPECT_FALSE(solver.Solve(c.X_WP, c.X_WS, true).cold_probes_resumed);
  }
  {
    PolyDepthSolver solver(c.P, c.S, options);
    ASSERT_FALSE(solver.Solve(c.X_WP, c.X_WS).converged);
    solver.ResetWarmStart();
    // Coherent but with nothing to follow: a cold query of its own.
    const PenetrationResult r = solver.Solve(c.X_WP, c.X_WS, true);
    EXPECT_FALSE(r.cold_probes_resumed);
    EXPECT_TRUE(r.warm_start_failed || r.starts > 0);
  }
}

// An unbounded cold query completes its search: nothing is left for the
// queries after it, whose answers are the same.
TEST(ColdFollowUp, AnUnboundedColdQueryLeavesNothing) {
  PD_REQUIRE_FILE(kMeshDir + "/dino.off", "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(kMeshDir + "/femur.off", "run scripts/fetch_meshes.sh");
  const DinoFemurPocket c;
  PolyDepthSolver solver(c.P, c.S);
  const PenetrationResult first = solver.Solve(c.X_WP, c.X_WS);
  ASSERT_TRUE(first.valid && first.converged);
  for (int k = 0; k < 3; ++k) {
    const PenetrationResult r = solver.Solve(c.X_WP, c.X_WS, true);
    EXPECT_FALSE(r.cold_probes_resumed);
    EXPECT_NEAR(r.depth, first.depth, 1e-9);
  }
}

// InnerProbeStarts stopped after every few probes and resumed from its
// cursor finds the same free probes, in the same order, as in one call.
TEST(InnerProbeStarts, ResumedFromItsCursorFindsWhatOneCallFinds) {
  // Two interlocked rings: free probes inside the answer exist.
  const Model ring = CollisionModel::Build(MakeTorus(0.05, 0.012, 48, 24));
  Isometry3 X_WP = Isometry3::Identity();
  X_WP.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3::UnitX()).toRotationMatrix();
  X_WP.translation() = Vector3(0.05, 0.004, 0.003);
  const ModelPair pair(*ring, *ring, X_WP, Isometry3::Identity());
  const double best_norm = 0.06;
  std::vector<Vector3> at_once;
  ASSERT_TRUE(InnerProbeStarts(pair, best_norm, 64, {0.3, 0.6, 0.9}, 1000, &at_once));
  ASSERT_GE(at_once.size(), 2u) << "the rings give no free probe: the test shows nothing";
  for (int every : {2, 3, 7}) {
    std::vector<Vector3> pieces;
    ProbeCursor cursor;
    int asked = 0, calls = 0;
    const std::function<bool()> stop = [&] { return ++asked % every == 0; };
    while (!InnerProbeStarts(pair, best_norm, 64, {0.3, 0.6, 0.9}, 1000, &pieces, stop, &cursor))
      ASSERT_LT(++calls, 1000);
    EXPECT_EQ(pieces, at_once) << "stopped every " << every;
  }
  // max_out counts over the pieces too.
  std::vector<Vector3> first_two;
  ProbeCursor cursor;
  int asked = 0;
  const std::function<bool()> stop = [&] { return ++asked % 2 == 0; };
  while (!InnerProbeStarts(pair, best_norm, 64, {0.3, 0.6, 0.9}, 2, &first_two, stop, &cursor)) {
  }
  ASSERT_EQ(first_two.size(), 2u);
  EXPECT_EQ(first_two[0], at_once[0]);
  EXPECT_EQ(first_two[1], at_once[1]);
}

}  // namespace
}  // namespace pd
