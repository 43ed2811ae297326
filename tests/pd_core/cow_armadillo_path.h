#pragma once
// bench_pd's cow_armadillo haptic pair (the cow scaled to a 2.5 cm tool, the
// armadillo to a 7.5 cm object, the object's centre at the origin of W as
// bench_pd places it) and a warm solve along rows of one of its recorded
// paths (`haptic_work --dump F --dump-poses`), scored at the last row
// against the independent reference PD.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <vector>

#include "pd_core/polydepth/polydepth.h"
#include "pd_core/reference/reference_pd.h"
#include "tests/pd_core/pair_pd_test_helpers.h"
#include "tests/pd_core/scaled_mesh_model.h"

namespace pd {
namespace test {

// x y z (m), qw qx qy qz of the tool in W, one row per millisecond.
using PathRows = std::vector<std::array<double, 7>>;

// The last answer of a warm solve along `rows` (from a cold start at the
// first) and the reference PD at that pose. Every pose must collide with a
// valid answer and none after the first may restart cold; the answer must
// be free by the reference's own test. Both depths go to the test's
// properties (depth_um, reference_um). Returns false (with the failures
// recorded) where a pose breaks that. With `all`, every pose's answer goes
// there too.
inline bool SolveCowArmadilloRows(const PathRows& rows, PenetrationResult* last,
                                  double* reference_depth,
                                  std::vector<PenetrationResult>* all = nullptr) {
  const auto tool = LoadScaled("cow.off", 0.047510300737962564);
  const auto object = LoadScaled("armadillo.off", 0.00080634978724717667);
  Isometry3 X_WS = Isometry3::Identity();
  X_WS.translation() = -object->center();
  PolyDepthSolver solver(tool, object);
  Isometry3 X_WP;
  for (size_t i = 0; i < rows.size(); ++i) {
    X_WP = PoseOfRow(rows[i]);
    *last = solver.Solve(X_WP, X_WS, /*coherent=*/true);
    if (all != nullptr) all->push_back(*last);
    EXPECT_TRUE(last->in_collision) << "pose " << i;
    EXPECT_TRUE(last->valid) << "pose " << i;
    EXPECT_FALSE(i > 0 && last->warm_start_failed) << "pose " << i;
    if (!last->in_collision || !last->valid) return false;
  }
  EXPECT_FALSE(ReferenceInCollision(tool->mesh(), X_WP, true, object->mesh(), X_WS, true,
                                    last->translation_W));
  const ReferencePdResult ref = ReferencePenetrationDepth(
      tool->mesh(), X_WP, true, object->mesh(), X_WS, true, BenchHapticReferenceOptions());
  EXPECT_TRUE(ref.in_collision);
  *reference_depth = ref.depth;
  ::testing::Test::RecordProperty("depth_um", static_cast<int>(last->depth * 1e6));
  ::testing::Test::RecordProperty("reference_um", static_cast<int>(ref.depth * 1e6));
  return ref.in_collision;
}

}  // namespace test
}  // namespace pd
