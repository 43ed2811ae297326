// A coherent answer that follows a drifting local optimum on real meshes:
// 28 poses of bench_pd's fandisk_elephant haptic path (poses 440-468, 1 ms
// apart, interpolated here between the two ends), where the followed answer
// turns away from its earlier direction and grows while a shallower escape
// opens back toward that direction. Scored against the independent reference
// PD at the last pose; and, bounded, where the checks of that drift wait;
// and a search that creeps across the contact on the same pair.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "pd_core/polydepth/polydepth.h"
#include "pd_core/reference/reference_pd.h"
#include "tests/pd_core/fandisk_on_elephant.h"
#include "tests/pd_core/pair_pd_test_helpers.h"

namespace pd {
namespace {

using test::Pose;

// bench_pd's fandisk_elephant pair (test::FandiskOnElephant: its meshes,
// scales and prerequisites) and the drift path: the tool's pose (in the
// object's frame S = W) at step i of kSteps, interpolated between the two
// ends as bench_pd makes them.
class CoherentBasinDrift : public test::FandiskOnElephant {
 protected:
  static constexpr int kSteps = 28;
  static Isometry3 DriftPose(int i) {
    const Vector3 p0(0.043860045513402203, -0.023996979285694404, 0.026112222875851313);
    const Quaternion q0(0.79013238350542736, 0.24056990352443952, 0.54975462791130669,
                        -0.12484705500881792);
    const Vector3 p1(0.043271143390655548, -0.020344178078998333, 0.02178685156320526);
    const Quaternion q1(0.78894881639903036, 0.23933698127630806, 0.55064487332792467,
                        -0.13064378275978922);
    const double t = static_cast<double>(i) / kSteps;
    return Pose((1.0 - t) * p0 + t * p1, q0.slerp(t, q1));
  }
};

// Before the probe back along the shallowest answer's direction (step 2c of
// PolyDepthSolver::Solve), the answer at the last pose was 1.72 mm against
// the reference's 1.08 (+59%: the bench's worst sampled pose on this path);
// the 2b cross-check only starts at 1.2x its anchor plus 5e-3 of the size.
TEST_F(CoherentBasinDrift, FandiskOnElephantAnswerReturnsToTheShallowerEscape) {
  const Isometry3 X_WS = Isometry3::Identity();
  PolyDepthSolver solver(tool, object);
  PenetrationResult r;
  Isometry3 X_WP;
  double shallowest = 1e300;
  for (int i = 0; i <= kSteps; ++i) {
    X_WP = DriftPose(i);
    r = solver.Solve(X_WP, X_WS, true);
    ASSERT_TRUE(r.in_collision) << "pose " << i;
    ASSERT_TRUE(r.valid) << "pose " << i;
    EXPECT_FALSE(r.warm_start_failed) << "pose " << i;
    shallowest = std::min(shallowest, r.depth);
  }
  EXPECT_FALSE(ReferenceInCollision(tool->mesh(), X_WP, true, object->mesh(), X_WS, true,
                                    r.translation_W));
  const ReferencePdResult ref = ReferencePenetrationDepth(
      tool->mesh(), X_WP, true, object->mesh(), X_WS, true, test::BenchHapticReferenceOptions());
  ASSERT_TRUE(ref.in_collision);
  // The path deepens by a few percent here; the followed optimum grew 40%
  // above the shallowest answer before the fix.
  EXPECT_LE(r.depth, 1.05 * ref.depth) << "reference " << ref.depth;
  EXPECT_LE(r.depth, 1.15 * shallowest);
}

// A bounded query (PolyDepthOptions::max_work) that is out of budget once it
// has an answer leaves the cross-check, the probe back along the anchor and
// the neighbour-basin probes (steps 2b, 2c and 2e) to the next query:
// optional work does not start past the budget. Unbounded, this path runs
// them.
TEST_F(CoherentBasinDrift, AQueryOutOfBudgetLeavesTheCrossCheckToTheNextOne) {
  PolyDepthOptions bounded;
  bounded.max_work = 1;  // spent by the time any answer exists
  PolyDepthSolver full(tool, object), quick(tool, object, bounded);
  int checked = 0, stopped = 0;
  for (int i = 0; i <= kSteps; ++i) {
    const PenetrationResult a = full.Solve(DriftPose(i), Isometry3::Identity(), true);
    checked += a.cross_checked || a.basin_probes > 0;
    const PenetrationResult b = quick.Solve(DriftPose(i), Isometry3::Identity(), true);
    ASSERT_TRUE(b.valid) << "pose " << i;
    stopped += !b.converged;
    EXPECT_FALSE(!b.converged && (b.cross_checked || b.basin_probes > 0)) << "pose " << i;
  }
  EXPECT_GT(checked, 0);
  EXPECT_GT(stopped, 20);
}

// A creeping search: the tool at pose 774 of bench_pd's fandisk_elephant
// haptic path (in the object's frame), then at pose 783 pushed 2 mm deeper.
// The coherent query there iterates 12 times across the contact, a few
// micrometres a step; from its 6th iteration on (the default
// PolyDepthOptions::creep_join_iterations), the local model keeps the earlier
// iterates' constraints still near, and the search ends in 8, 3.8% deeper.
TEST_F(CoherentBasinDrift, ACreepingSearchKeepsTheEarlierIteratesConstraints) {
  const Isometry3 X_WP0 =
      Pose(Vector3(0.036932999139936536, 0.010280456190993449, -0.014402275741055941),
           Quaternion(0.77410547538283159, 0.22529092567685494, 0.55902803830960979,
                      -0.19362945068789389));
  const Isometry3 X_WP1 =
      Pose(Vector3(0.036879519156057521, 0.011236158291516293, -0.015539278097795347 - 2e-3),
           Quaternion(0.77361633619682546, 0.22486229423482695, 0.55923705497471388,
                      -0.19547027739290493));
  const Isometry3 X_WS = Isometry3::Identity();
  PolyDepthOptions off;
  off.creep_join_iterations = 0;
  PolyDepthSolver without(tool, object, off), with(tool, object);
  without.Solve(X_WP0, X_WS, true);
  with.Solve(X_WP0, X_WS, true);
  const PenetrationResult a = without.Solve(X_WP1, X_WS, true);
  const PenetrationResult b = with.Solve(X_WP1, X_WS, true);
  ASSERT_TRUE(a.valid);
  ASSERT_TRUE(b.valid);
  EXPECT_EQ(a.initializer, Initializer::kMotionCoherence);
  EXPECT_EQ(b.initializer, Initializer::kMotionCoherence);
  EXPECT_GE(a.iterations, 10);
  EXPECT_LT(b.iterations, a.iterations - 2);
  EXPECT_LT(b.box_tests + b.triangle_tests, a.box_tests + a.triangle_tests);
  // Still an escape, and near the creeping search's.
  EXPECT_FALSE(ReferenceInCollision(tool->mesh(), X_WP1, true, object->mesh(), X_WS, true,
                                    b.translation_W));
  EXPECT_LE(b.depth, 1.05 * a.depth);
}

}  // namespace
}  // namespace pd
