// Surface intersection (pd_core/proximity/mesh_collision.h) on real meshes:
// its verdict equals a brute force over all triangle pairs, and on colliding
// configurations the descent visits the most deeply overlapping node pair
// first, so it reaches an intersecting triangle pair after few box tests
// (the cold solve's inner probes make ~100 such tests per query).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <string>

#include "pd_core/geometry/fibonacci_sphere.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"
#include "pd_core/proximity/triangle_geometry.h"
#include "tests/pd_core/brute_force_pairs.h"
#include "tests/prerequisites.h"

namespace pd {
namespace {

using Model = std::shared_ptr<const CollisionModel>;
const std::string kMeshDir = PD_TEST_MESH_DIR;

// Any probe triangle crossing any scene triangle, over all pairs (no BVH).
bool BruteForceSurfacesIntersect(const ModelPair& pair, const Vector3& offset_S) {
  bool hit = false;
  test::ForEachOverlappingTrianglePair(pair, offset_S, Vector3::Zero(), [&](int tp, int ts) {
    Vector3 p[3], s[3];
    pair.ProbeTriangle(tp, offset_S, p);
    pair.SceneTriangle(ts, s);
    hit = TrianglesIntersect(p[0], p[1], p[2], s[0], s[1], s[2]);
    return !hit;
  });
  return hit;
}

TEST(SurfacesIntersect, DeepConfigurationsOfRealMeshesFindACrossingAfterFewBoxTests) {
  PD_REQUIRE_FILE(kMeshDir + "/cow.off", "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(kMeshDir + "/knot1.off", "run scripts/fetch_meshes.sh");
  const Model P = test::LoadCentredModel(kMeshDir + "/cow.off"),
              S = test::LoadCentredModel(kMeshDir + "/knot1.off");
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g;
  ProximityCounters counters;
  int colliding = 0, checked = 0;
  for (int k = 0; k < 8; ++k) {
    Isometry3 X_WP = Isometry3::Identity();
    X_WP.linear() = Quaternion(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    X_WP.translation() = S->center() - X_WP.linear() * P->center();
    ModelPair pair(*P, *S, X_WP, Isometry3::Identity());
    // The inner probes of a cold query 40 mm deep: 0.7 of that along 48 directions.
    for (int i = 0; i < 48; ++i) {
      const Vector3 q = 0.7 * 0.04 * FibonacciDirection(i, 48);
      pair.counters = &counters;
      const bool hit = SurfacesIntersect(pair, q);
      pair.counters = nullptr;
      colliding += hit;
      if (i % 16 == 0) {
        EXPECT_EQ(hit, BruteForceSurfacesIntersect(pair, q)) << "pose " << k << " direction " << i;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 24);
  EXPECT_GE(colliding, 300);
  const double per_test = static_cast<double>(counters.box_tests) / (8 * 48);
  // Measured 113 per test; 275 with the children visited in index order.
  EXPECT_LT(per_test, 160.0) << colliding << " of 384 colliding";
}

}  // namespace
}  // namespace pd
