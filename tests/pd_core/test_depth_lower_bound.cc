// The PD lower bound from an answer's own contact (depth_lower_bound.h) and
// the point-clearance query under it (point_clearance.h): clearance against
// a brute-force distance, the bound against an analytic PD on boxes (proved
// where the answer is shortest, never where a shorter exit exists), and on
// real meshes against the independent reference's exit distances: no
// direction leaves in less than a proved bound.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>

#include "pd_core/geometry/fibonacci_sphere.h"
#include "pd_core/geometry/make_shapes.h"
#include "pd_core/mesh/load_mesh.h"
#include "pd_core/polydepth/contact_constraints.h"
#include "pd_core/polydepth/depth_lower_bound.h"
#include "pd_core/polydepth/polydepth.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/point_clearance.h"
#include "pd_core/reference/reference_pd.h"
#include "tests/pd_core/point_triangle_distance.h"
#include "tests/pd_core/scaled_mesh_model.h"
#include "tests/prerequisites.h"

namespace pd {
namespace {

using Model = std::shared_ptr<const CollisionModel>;

Isometry3 At(const Vector3& p) { return MakePose(p, 1, 0, 0, 0); }


TEST(PointClearance, AgreesWithBruteForceDistanceOnARealMesh) {
  const std::string path = std::string(PD_TEST_MESH_DIR) + "/cow.off";
  PD_REQUIRE_FILE(path, "run scripts/fetch_meshes.sh");
  Model cow = test::LoadScaled("cow.off", 1.0);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  std::uniform_int_distribution<int> pick(0, cow->mesh().num_vertices() - 1);
  int decided_near = 0;
  for (int i = 0; i < 200; ++i) {
    // Points near the surface (inside and outside), where the BVH prunes least.
    const Vector3 p = cow->mesh().vertices[pick(rng)] +
                      0.02 * cow->radius() * Vector3(g(rng), g(rng), g(rng));
    const double d = test::BruteForceSurfaceDistance(cow->mesh(), p);
    ProximityCounters counters;
    EXPECT_TRUE(SurfaceFartherThan(*cow, p, d * (1 - 1e-9), &counters)) << i << " d=" << d;
    EXPECT_FALSE(SurfaceFartherThan(*cow, p, d * (1 + 1e-9) + 1e-15)) << i << " d=" << d;
    // Pruned: far fewer node tests than the tree has nodes.
    EXPECT_LT(counters.box_tests, static_cast<int64_t>(cow->bvh().nodes().size()) / 4) << i;
    decided_near += d < 0.01 * cow->radius();
  }
  EXPECT_GT(decided_near, 20);
}

// A cube of half-size h pressed depth d into the top face (z = H) of a large
// box, at (x, 0): PD = min(d, the way out sideways past the edge at x = H).
struct PressedCube {
  Model cube = CollisionModel::Build(MakeBox(Vector3::Constant(0.01)));
  Model block = CollisionModel::Build(MakeBox(Vector3::Constant(0.1)));
  std::vector<ContactConstraint> at_answer;
  // Localises at the answer `q_S` (touching) for the cube at (x, 0, z).
  ModelPair At(double x, double z, const Vector3& q_S) {
    ModelPair pair(*cube, *block, pd::At(Vector3(x, 0, z)), Isometry3::Identity());
    CollectContactConstraints(pair, q_S, 1e-4 * pair.size(), &at_answer);
    return pair;
  }
};

TEST(DepthLowerBound, ProvesAPressedCubesUpwardAnswerAndNoMore) {
  PressedCube c;
  const double d = 0.002;
  // The cube's bottom face sits d below the top face, far from the edges.
  const ModelPair pair = c.At(0.0, 0.1 + 0.01 - d, Vector3(0, 0, d));
  ASSERT_FALSE(c.at_answer.empty());
  EXPECT_TRUE(ProvesDepthAtLeast(pair, c.at_answer, 0.99 * d));
  EXPECT_FALSE(ProvesDepthAtLeast(pair, c.at_answer, 1.01 * d));
}

TEST(DepthLowerBound, NeverProvesAnAnswerLongerThanASidewaysExit) {
  PressedCube c;
  const double d = 0.004;
  // Near the block's edge: the cube overhangs to 1 mm from the edge, so it
  // leaves sideways in 0.1 + 0.01 - x = 1 mm, shorter than the upward d.
  const double x = 0.1 + 0.01 - 0.001;
  const ModelPair pair = c.At(x, 0.1 + 0.01 - d, Vector3(0, 0, d));
  ASSERT_FALSE(c.at_answer.empty());
  EXPECT_FALSE(ProvesDepthAtLeast(pair, c.at_answer, 0.9 * d));
  EXPECT_FALSE(ProvesDepthAtLeast(pair, c.at_answer, 0.3 * d));
  // What it may prove is no more than the sideways exit.
  EXPECT_FALSE(ProvesDepthAtLeast(pair, c.at_answer, 0.0011));
}

TEST(DepthLowerBound, OpenMeshesProveNothing) {
  // Without a closed other model, inside is undefined: no certificate.
  TriangleMesh open = MakeBox(Vector3::Constant(0.1));
  open.triangles.pop_back();
  Model cube = CollisionModel::Build(MakeBox(Vector3::Constant(0.01)));
  Model sheet = CollisionModel::Build(std::move(open));
  ASSERT_FALSE(sheet->closed());
  const double d = 0.002;
  ModelPair pair(*cube, *sheet, At(Vector3(0, 0, 0.1 + 0.01 - d)), Isometry3::Identity());
  std::vector<ContactConstraint> at_answer;
  CollectContactConstraints(pair, Vector3(0, 0, d), 1e-4 * pair.size(), &at_answer);
  ASSERT_FALSE(at_answer.empty());
  EXPECT_FALSE(ProvesDepthAtLeast(pair, at_answer, 0.5 * d));
}

// Real meshes at haptic depths: a 5 cm cow tool pressed a few millimetres
// into a 15 cm armadillo, answered by PolyDepth. The largest bound the
// answer's contact proves (bisection) must be no longer than the exact exit
// distance along every one of 48 directions (the reference's, written
// independently of pd_core's queries), and no longer than the answer.
TEST(DepthLowerBound, NoDirectionLeavesShorterThanAProvedBoundOnRealMeshes) {
  const std::string tool = std::string(PD_TEST_MESH_DIR) + "/cow.off";
  const std::string object = std::string(PD_TEST_MESH_DIR) + "/armadillo.off";
  PD_REQUIRE_FILE(tool, "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(object, "run scripts/fetch_meshes.sh");
  Model raw_P = test::LoadScaled("cow.off", 1.0), raw_S = test::LoadScaled("armadillo.off", 1.0);
  Model P = test::LoadScaled("cow.off", 0.025 / raw_P->radius());
  Model S = test::LoadScaled("armadillo.off", 0.075 / raw_S->radius());
  const Isometry3 X_WS = Isometry3::Identity();
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  std::uniform_int_distribution<int> pick(0, S->mesh().num_vertices() - 1);
  int proved = 0, poses = 0;
  for (int tries = 0; tries < 400 && poses < 8; ++tries) {
    // The tool's centre placed 1-4 mm inside its own radius from a scene
    // vertex, along that vertex's outward offset from the scene centre.
    const Vector3 v = S->mesh().vertices[pick(rng)];
    const Vector3 out = (v - S->center()).normalized();
    Isometry3 X_WP = Isometry3::Identity();
    X_WP.linear() = Quaternion(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    const double inset = 0.001 + 0.003 * std::abs(g(rng)) / 2;
    X_WP.translation() = v + (P->radius() * 0.5 - inset) * out - X_WP.linear() * P->center();
    ModelPair pair(*P, *S, X_WP, X_WS);
    if (!InCollision(pair, Vector3::Zero())) continue;
    const PenetrationResult r = PolyDepthSolver(P, S).Solve(X_WP, X_WS);
    ASSERT_TRUE(r.valid);
    if (r.depth <= 0.0) continue;
    ++poses;
    std::vector<ContactConstraint> at_answer;
    CollectContactConstraints(pair, r.translation_W, 1e-4 * pair.size(), &at_answer);
    if (!ProvesDepthAtLeast(pair, at_answer, 1e-6 * r.depth)) continue;
    double lo = 1e-6 * r.depth, hi = 2.0 * r.depth;
    for (int k = 0; k < 30; ++k) {
      const double mid = 0.5 * (lo + hi);
      (ProvesDepthAtLeast(pair, at_answer, mid) ? lo : hi) = mid;
    }
    ++proved;
    EXPECT_LE(lo, r.depth * (1 + 1e-9)) << "pose " << poses;
    for (int i = 0; i < 48; ++i) {
      const Vector3 u = FibonacciDirection(i, 48);
      const double exit = DirectionalPenetration(P->mesh(), X_WP, true, S->mesh(), X_WS, true, u,
                                                 1e-9 * pair.size());
      EXPECT_GE(exit, lo * (1 - 1e-9)) << "pose " << poses << " direction " << i;
    }
  }
  std::printf("[ bound    ] %d of %d answers proved within their own length\n", proved, poses);
  EXPECT_EQ(poses, 8);
  EXPECT_GE(proved, 2);
}

}  // namespace
}  // namespace pd
