// Closed-form PD (half-space, swept spheres, sphere-box) against analytic
// answers and against the reference PD on tessellations; touching, separated
// and contained cases; rotated frames; scale 1e-4 and 1e3.
//
// Reference comparisons use tessellations with a chord error of 2% of the
// radius (circumscribed), so the reference can differ from the exact PD by
// at most the sum of the two tessellation errors (measured per mesh) plus its
// own convergence (1e-4 of the size is allowed).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pd_core/convex/closed_form_pd.h"
#include "pd_core/geometry/make_shapes.h"
#include "pair_pd_test_helpers.h"

namespace pd {
namespace {

using test::Pose;
using G = std::shared_ptr<const Geometry>;

PairPdAnswer Solve(const G& P, const Isometry3& X_WP, const G& S, const Isometry3& X_WS) {
  return ClosedFormPenetrationDepth(*P, X_WP, *S, X_WS);
}

TEST(ClosedFormPd, SphereSphereAnalytic) {
  auto a = Geometry::MakeSphere(0.3), b = Geometry::MakeSphere(0.5);
  const Vector3 dir = Vector3(1, 2, -0.5).normalized();
  PairPdAnswer r = Solve(a, Pose(0.6 * dir), b, Pose(Vector3::Zero()));
  ASSERT_TRUE(r.in_collision);
  EXPECT_NEAR(r.depth, 0.2, 1e-15);
  EXPECT_NEAR((r.normal_W - dir).norm(), 0.0, 1e-15);
  // Concentric: any direction, depth r1 + r2.
  r = Solve(a, Pose(Vector3(1, 1, 1)), b, Pose(Vector3(1, 1, 1)));
  EXPECT_NEAR(r.depth, 0.8, 1e-15);
  EXPECT_NEAR(r.normal_W.norm(), 1.0, 1e-15);
  // Touching and apart: free.
  EXPECT_FALSE(Solve(a, Pose(0.8 * dir), b, Pose(Vector3::Zero())).in_collision);
  EXPECT_FALSE(Solve(a, Pose(0.9 * dir), b, Pose(Vector3::Zero())).in_collision);
}

TEST(ClosedFormPd, PrimitivesOnATiltedPlaneAnalytic) {
  std::mt19937 rng(11);
  auto plane = Geometry::MakeHalfSpace();
  auto sphere = Geometry::MakeSphere(0.2);
  auto box = Geometry::MakeBox(Vector3(0.1, 0.2, 0.3));
  auto capsule = Geometry::MakeCapsule(0.05, 0.2);
  auto cylinder = Geometry::MakeCylinder(0.1, 0.25);
  for (int i = 0; i < 30; ++i) {
    const Isometry3 X_WS = Pose(Vector3(0.1, -0.2, 0.3), test::RandomRotation(rng));
    const Vector3 n = X_WS.linear().col(2);
    const Isometry3 X_WP = Pose(X_WS.translation() + 0.1 * n + Vector3(0.02, 0.03, -0.01),
                                test::RandomRotation(rng));
    const double h = n.dot(X_WP.translation() - X_WS.translation());  // centre height
    const Vector3 a = X_WP.linear().col(2);                           // probe axis
    const double c = std::abs(a.dot(n)), s = std::sqrt(std::max(0.0, 1 - c * c));
    double box_low = 1e300;
    for (int k = 0; k < 8; ++k) {
      const Vector3 corner((k & 1 ? 1 : -1) * 0.1, (k & 2 ? 1 : -1) * 0.2, (k & 4 ? 1 : -1) * 0.3);
      box_low = std::min(box_low, n.dot(X_WP.linear() * corner));
    }
    const struct { G g; double expected; } cases[] = {
        {sphere, 0.2 - h},
        {box, -(h + box_low)},
        {capsule, 0.2 * c + 0.05 - h},
        {cylinder, 0.25 * c + 0.1 * s - h},
    };
    for (const auto& k : cases) {
      const PairPdAnswer r = Solve(k.g, X_WP, plane, X_WS);
      ASSERT_EQ(r.in_collision, k.expected > 0) << k.g->Describe() << " case " << i;
      if (!r.in_collision) continue;
      EXPECT_NEAR(r.depth, k.expected, 1e-14) << k.g->Describe();
      EXPECT_NEAR((r.normal_W - n).norm(), 0.0, 1e-14);
    }
  }
}

// A general (non-convex) mesh on a plane: exact for any mesh.
TEST(ClosedFormPd, NonConvexMeshOnPlaneIsItsDeepestVertex) {
  auto torus = Geometry::MakeMesh(CollisionModel::Build(MakeTorus(0.1, 0.03, 32, 12)));
  auto plane = Geometry::MakeHalfSpace();
  std::mt19937 rng(5);
  for (int i = 0; i < 10; ++i) {
    const Isometry3 X_WP = Pose(Vector3(0, 0, 0.05), test::RandomRotation(rng));
    double low = 1e300;
    for (const Vector3& v : torus->model()->mesh().vertices) low = std::min(low, (X_WP * v).z());
    const PairPdAnswer r = Solve(torus, X_WP, plane, Pose(Vector3::Zero()));
    ASSERT_EQ(r.in_collision, low < 0);
    if (r.in_collision) EXPECT_NEAR(r.depth, -low, 1e-15);
  }
}

TEST(ClosedFormPd, SphereBoxFaceEdgeCornerAndInside) {
  auto sphere = Geometry::MakeSphere(0.1);
  auto box = Geometry::MakeBox(Vector3(0.5, 0.4, 0.3));
  const Isometry3 X_WS = Pose(Vector3(1, 2, 3), Quaternion(0.9, 0.1, -0.3, 0.2));
  struct Case { Vector3 c_S; double depth; Vector3 n_S; };
  const double e = 0.04 / std::sqrt(2.0), k = 0.05 / std::sqrt(3.0);
  const Case cases[] = {
      {Vector3(0.2, 0.1, 0.35), 0.05, Vector3::UnitZ()},                  // face
      {Vector3(0.5 + e, 0.4 + e, 0.0), 0.06, Vector3(1, 1, 0).normalized()},  // edge
      {Vector3(-0.5 - k, 0.4 + k, -0.3 - k), 0.05, Vector3(-1, 1, -1).normalized()},  // corner
      {Vector3(0.1, -0.35, 0.0), 0.15, -Vector3::UnitY()},                 // centre inside
      {Vector3(0.0, 0.0, 0.0), 0.4, Vector3::UnitZ()},                     // deep
  };
  for (const Case& c : cases) {
    const Isometry3 X_WP = Pose(X_WS * c.c_S);
    PairPdAnswer r = Solve(sphere, X_WP, box, X_WS);
    ASSERT_TRUE(r.in_collision) << c.c_S.transpose();
    EXPECT_NEAR(r.depth, c.depth, 1e-14);
    EXPECT_NEAR((r.normal_W - X_WS.linear() * c.n_S).norm(), 0.0, 1e-12);
    // Swapped roles: same depth, opposite direction.
    r = Solve(box, X_WS, sphere, X_WP);
    EXPECT_NEAR(r.depth, c.depth, 1e-14);
    EXPECT_NEAR((r.normal_W + X_WS.linear() * c.n_S).norm(), 0.0, 1e-12);
  }
  EXPECT_FALSE(Solve(sphere, Pose(X_WS * Vector3(0, 0, 0.4)), box, X_WS).in_collision);  // touching
}

TEST(ClosedFormPd, CapsulesCrossingParallelAndEndOn) {
  auto a = Geometry::MakeCapsule(0.05, 0.3), b = Geometry::MakeCapsule(0.08, 0.2);
  auto s = Geometry::MakeSphere(0.1);
  // Crossing at right angles, axes 0.1 apart: PD 0.13 - 0.1 along the gap.
  const Isometry3 X_WS = Pose(Vector3::Zero(), Quaternion(Eigen::AngleAxisd(M_PI / 2, Vector3::UnitX())));
  PairPdAnswer r = Solve(a, Pose(Vector3(0.1, 0.0, 0.1)), b, X_WS);
  ASSERT_TRUE(r.in_collision);
  EXPECT_NEAR(r.depth, 0.03, 1e-14);
  EXPECT_NEAR((r.normal_W - Vector3::UnitX()).norm(), 0.0, 1e-12);
  // Axes intersecting: PD = r1 + r2 along the common normal of the axes.
  r = Solve(a, Pose(Vector3::Zero()), b, X_WS);
  EXPECT_NEAR(r.depth, 0.13, 1e-14);
  EXPECT_NEAR(std::abs(r.normal_W.x()), 1.0, 1e-12);
  // Parallel overlapping axes: perpendicular exit, depth r1 + r2.
  r = Solve(a, Pose(Vector3(0, 0, 0.1)), b, Pose(Vector3::Zero()));
  EXPECT_NEAR(r.depth, 0.13, 1e-14);
  EXPECT_NEAR(r.normal_W.z(), 0.0, 1e-12);
  // End-on: tip to tip along z, overlap 0.02.
  r = Solve(a, Pose(Vector3(0, 0, 0.3 + 0.05 + 0.2 + 0.08 - 0.02)), b, Pose(Vector3::Zero()));
  EXPECT_NEAR(r.depth, 0.02, 1e-14);
  EXPECT_NEAR((r.normal_W - Vector3::UnitZ()).norm(), 0.0, 1e-12);
  // Sphere centred on the capsule axis.
  r = Solve(s, Pose(Vector3(0, 0, 0.1)), a, Pose(Vector3::Zero()));
  EXPECT_NEAR(r.depth, 0.15, 1e-14);
  EXPECT_NEAR(r.normal_W.z(), 0.0, 1e-12);
}

TEST(ClosedFormPd, ScaleInvariance) {
  std::mt19937 rng(9);
  const G shapes[][2] = {
      {Geometry::MakeCapsule(0.05, 0.3), Geometry::MakeCapsule(0.08, 0.2)},
      {Geometry::MakeSphere(0.1), Geometry::MakeBox(Vector3(0.2, 0.3, 0.1))},
      {Geometry::MakeCylinder(0.1, 0.2), Geometry::MakeHalfSpace()}};
  for (const auto& pair : shapes) {
    const Isometry3 X_WP = Pose(Vector3(0.01, 0.02, 0.03), test::RandomRotation(rng));
    const Isometry3 X_WS = Pose(Vector3(0, 0.02, 0), test::RandomRotation(rng));
    const PairPdAnswer r1 = Solve(pair[0], X_WP, pair[1], X_WS);
    ASSERT_TRUE(r1.in_collision) << pair[0]->Describe();
    for (double k : {1e-4, 1e3}) {
      auto scaled = [k](const G& g) -> G {
        switch (g->kind()) {
          case ShapeKind::kSphere: return Geometry::MakeSphere(k * g->sphere().radius);
          case ShapeKind::kBox: return Geometry::MakeBox(k * g->box().half_extents);
          case ShapeKind::kCapsule: return Geometry::MakeCapsule(k * g->capsule().radius, k * g->capsule().half_length);
          case ShapeKind::kCylinder: return Geometry::MakeCylinder(k * g->cylinder().radius, k * g->cylinder().half_length);
          default: return g;
        }
      };
      Isometry3 P = X_WP, S = X_WS;
      P.translation() *= k, S.translation() *= k;
      const PairPdAnswer rk = Solve(scaled(pair[0]), P, scaled(pair[1]), S);
      ASSERT_TRUE(rk.in_collision);
      EXPECT_NEAR(rk.depth / k, r1.depth, 1e-12 * r1.depth) << pair[0]->Describe() << " x" << k;
      EXPECT_NEAR((rk.normal_W - r1.normal_W).norm(), 0.0, 1e-9);
    }
  }
}

// Every closed form against the slow reference on 2% tessellations.
TEST(ClosedFormPd, MatchesReferenceOnTessellations) {
  std::mt19937 rng(21);
  const G plane = Geometry::MakeHalfSpace();
  const G pairs[][2] = {
      {Geometry::MakeSphere(0.1), Geometry::MakeSphere(0.15)},
      {Geometry::MakeSphere(0.1), plane},
      {Geometry::MakeBox(Vector3(0.1, 0.05, 0.08)), plane},
      {Geometry::MakeCapsule(0.04, 0.1), plane},
      {Geometry::MakeCylinder(0.06, 0.1), plane},
      {Geometry::MakeSphere(0.08), Geometry::MakeBox(Vector3(0.1, 0.12, 0.07))},
      {Geometry::MakeBox(Vector3(0.1, 0.12, 0.07)), Geometry::MakeSphere(0.08)},
      {Geometry::MakeSphere(0.06), Geometry::MakeCapsule(0.05, 0.1)},
      {Geometry::MakeCapsule(0.05, 0.1), Geometry::MakeCapsule(0.04, 0.12)},
  };
  double worst = 0.0;
  for (const auto& pair : pairs) {
    for (int i = 0; i < 2; ++i) {
      const Isometry3 X_WS = Pose(Vector3::Zero(), test::RandomRotation(rng));
      Isometry3 X_WP;
      PairPdAnswer r;
      do {  // a colliding pose
        std::uniform_real_distribution<double> U(-0.12, 0.12);
        X_WP = Pose(Vector3(U(rng), U(rng), U(rng)), test::RandomRotation(rng));
        r = Solve(pair[0], X_WP, pair[1], X_WS);
      } while (!r.in_collision || r.depth < 0.01);
      double tess = 0.0;
      const ReferencePdResult ref =
          test::ReferenceOnTessellations(*pair[0], X_WP, *pair[1], X_WS, 0.02, &tess);
      const double size = pair[0]->radius() + (pair[1]->bounded() ? pair[1]->radius() : 0.0);
      // The tessellations contain the shapes, so the reference is deeper by
      // at most the tessellation error and never shallower (up to its tolerance).
      EXPECT_LE(ref.depth, r.depth + tess + 1e-4 * size) << pair[0]->Describe() << " vs " << pair[1]->Describe();
      EXPECT_GE(ref.depth, r.depth - 1e-4 * size) << pair[0]->Describe() << " vs " << pair[1]->Describe();
      worst = std::max(worst, std::abs(ref.depth - r.depth) / size);
    }
  }
  RecordProperty("worst_relative_difference", std::to_string(worst));
}

}  // namespace
}  // namespace pd
