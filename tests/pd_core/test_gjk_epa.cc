// Our GJK + EPA (pd_core/convex/convex_pd.h) against analytic answers, the slow
// reference PD (exact for polytopes; on 2% tessellations for curved
// primitives, within their measured tessellation error) and FCL 0.7's own
// GJK/EPA as a cross-check: ours must be at least as accurate as FCL on every
// case, and the test reports how far FCL is off.
#include <gtest/gtest.h>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <cmath>
#include <random>

#include "pd_core/convex/convex_pd.h"
#include "pd_core/geometry/make_shapes.h"
#include "pair_pd_test_helpers.h"

namespace pd {
namespace {

using test::Pose;
using G = std::shared_ptr<const Geometry>;

PairPdAnswer Ours(const G& P, const Isometry3& X_WP, const G& S, const Isometry3& X_WS) {
  static EpaScratch scratch;
  return ConvexPenetrationDepth(*P, X_WP, *S, X_WS, ConvexPdOptions{}, Vector3::Zero(), &scratch);
}

// The probe moved by the answer no longer overlaps (GJK signed distance,
// touching allowed within 1e-9 of the size).
void ExpectFreeAfter(const G& P, const Isometry3& X_WP, const G& S, const Isometry3& X_WS,
                     const PairPdAnswer& r, const std::string& label) {
  const double size = P->radius() + S->radius();
  const Isometry3 moved = TranslatedPose(X_WP, (r.depth + 1e-9 * size) * r.normal_W);
  EXPECT_GE(ConvexDistance(*P, moved, *S, X_WS), 0.0) << label;
}

// FCL's geometry for ours: primitives as FCL primitives (FCL then runs its
// GJK/EPA on their support functions), meshes as fcl::Convex.
std::shared_ptr<fcl::CollisionGeometryd> ToFcl(const Geometry& g) {
  switch (g.kind()) {
    case ShapeKind::kBox: return std::make_shared<fcl::Boxd>(2.0 * g.box().half_extents);
    case ShapeKind::kCylinder:
      return std::make_shared<fcl::Cylinderd>(g.cylinder().radius, 2.0 * g.cylinder().half_length);
    case ShapeKind::kCapsule:
      return std::make_shared<fcl::Capsuled>(g.capsule().radius, 2.0 * g.capsule().half_length);
    default: {
      const TriangleMesh& m = g.model()->mesh();
      auto verts = std::make_shared<std::vector<fcl::Vector3d>>(m.vertices.begin(), m.vertices.end());
      auto faces = std::make_shared<std::vector<int>>();
      for (const auto& t : m.triangles) faces->insert(faces->end(), {3, t[0], t[1], t[2]});
      return std::make_shared<fcl::Convexd>(verts, m.num_triangles(), faces);
    }
  }
}

// FCL's PD (|penetration_depth| of its single contact), -1 if it reports no collision.
double FclDepth(const Geometry& P, const Isometry3& X_WP, const Geometry& S, const Isometry3& X_WS,
                fcl::GJKSolverType solver) {
  fcl::CollisionObjectd oP(ToFcl(P), X_WP), oS(ToFcl(S), X_WS);
  fcl::CollisionRequestd request(1, true);
  request.gjk_solver_type = solver;
  fcl::CollisionResultd result;
  fcl::collide(&oP, &oS, request, result);
  return result.isCollision() ? std::abs(result.getContact(0).penetration_depth) : -1.0;
}

G BoxMesh(const Vector3& h) { return Geometry::MakeConvexMesh(CollisionModel::Build(MakeBox(h))); }

TEST(GjkEpa, AxisAlignedBoxesFaceFaceAnalytic) {
  const Vector3 hp(0.5, 0.3, 0.2), hs(1.0, 0.8, 0.6);
  auto P = Geometry::MakeBox(hp), S = Geometry::MakeBox(hs);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int i = 0; i < 100; ++i) {
    const Vector3 c(U(rng) * 1.4, U(rng) * 1.0, U(rng) * 0.75);
    double expected = 1e300;
    Vector3 dir;
    bool overlap = true;
    for (int k = 0; k < 3; ++k) {
      if (hp[k] + hs[k] - std::abs(c[k]) <= 0) overlap = false;
      const double out_pos = hs[k] + hp[k] - c[k], out_neg = hs[k] + hp[k] + c[k];
      if (out_pos < expected) expected = out_pos, dir = Vector3::Unit(k);
      if (out_neg < expected) expected = out_neg, dir = -Vector3::Unit(k);
    }
    const PairPdAnswer r = Ours(P, Pose(c), S, Pose(Vector3::Zero()));
    ASSERT_EQ(r.in_collision, overlap) << "case " << i;
    if (!overlap) continue;
    EXPECT_NEAR(r.depth, expected, 1e-9 * 2.3) << "case " << i;
    EXPECT_NEAR((r.normal_W - dir).norm(), 0.0, 1e-6) << "case " << i;
    ExpectFreeAfter(P, Pose(c), S, Pose(Vector3::Zero()), r, "face-face");
  }
}

// Rotated boxes (primitive and the same boxes as convex meshes) against the
// reference, exact for polytopes, and against FCL.
TEST(GjkEpa, RotatedBoxesAndConvexMeshesMatchReferenceAndBeatFcl) {
  std::mt19937 rng(17);
  const Vector3 hp(0.3, 0.2, 0.1), hs(0.4, 0.25, 0.3);
  const G sphere_hull = Geometry::MakeConvexMesh(CollisionModel::Build(MakeIcosphere(0.25, 2)));
  const G pairs[][2] = {{Geometry::MakeBox(hp), Geometry::MakeBox(hs)},
                        {BoxMesh(hp), BoxMesh(hs)},
                        {sphere_hull, BoxMesh(hs)},
                        {BoxMesh(hp), sphere_hull}};
  double worst_ours = 0.0, worst_fcl[2] = {0.0, 0.0};
  int fcl_wrong[2] = {0, 0}, total = 0;
  for (const auto& pair : pairs) {
    const double size = pair[0]->radius() + pair[1]->radius();
    for (int i = 0; i < 6; ++i) {
      const Isometry3 X_WS = Pose(Vector3(0.1, 0, 0), test::RandomRotation(rng));
      std::uniform_real_distribution<double> U(-0.35, 0.35);
      const Isometry3 X_WP = Pose(X_WS.translation() + Vector3(U(rng), U(rng), U(rng)),
                                  test::RandomRotation(rng));
      const PairPdAnswer r = Ours(pair[0], X_WP, pair[1], X_WS);
      double tess = 0.0;
      const ReferencePdResult ref =
          test::ReferenceOnTessellations(*pair[0], X_WP, *pair[1], X_WS, 0.02, &tess, 600);
      ASSERT_EQ(r.in_collision, ref.in_collision && ref.depth > 0) << "case " << i;
      if (!r.in_collision) continue;
      ++total;
      // Ours is a certified upper bound; it must be as tight as the reference.
      EXPECT_LE(r.depth, ref.depth + 1e-7 * size) << pair[0]->Describe() << " case " << i;
      ExpectFreeAfter(pair[0], X_WP, pair[1], X_WS, r, "rotated");
      worst_ours = std::max(worst_ours, std::abs(r.depth - ref.depth) / ref.depth);
      for (int k = 0; k < 2; ++k) {
        const double f = FclDepth(*pair[0], X_WP, *pair[1], X_WS, k ? fcl::GST_INDEP : fcl::GST_LIBCCD);
        if (f < 0) continue;
        const double err = std::abs(f - ref.depth) / ref.depth;
        worst_fcl[k] = std::max(worst_fcl[k], err);
        if (err > 1e-3) ++fcl_wrong[k];
        EXPECT_LE(std::abs(r.depth - ref.depth), std::abs(f - ref.depth) + 1e-7 * size);
      }
    }
  }
  std::printf("rotated convex pairs: %d colliding; worst relative error ours %.2e; FCL libccd "
              "%.2e (%d off by > 0.1%%), FCL GST_INDEP %.2e (%d off by > 0.1%%)\n",
              total, worst_ours, worst_fcl[0], fcl_wrong[0], worst_fcl[1], fcl_wrong[1]);
  EXPECT_LT(worst_ours, 1e-6);
  RecordProperty("worst_ours", std::to_string(worst_ours));
  RecordProperty("worst_fcl_libccd", std::to_string(worst_fcl[0]));
  RecordProperty("worst_fcl_indep", std::to_string(worst_fcl[1]));
}

// Edge-edge: two boxes crossed at 45 degrees, edges meeting.
TEST(GjkEpa, EdgeEdgeBoxes) {
  const Quaternion qa(Eigen::AngleAxisd(M_PI / 4, Vector3::UnitX()));
  const Quaternion qb(Eigen::AngleAxisd(M_PI / 4, Vector3::UnitY()));
  auto P = Geometry::MakeBox(Vector3(0.5, 0.1, 0.1)), S = Geometry::MakeBox(Vector3(0.1, 0.5, 0.1));
  // The lower edge of P (along x) crosses the upper edge of S (along y);
  // both edges are at distance 0.1 sqrt(2) from their box centres.
  const double e = 0.1 * std::sqrt(2.0);
  const double overlap = 0.01;
  const Isometry3 X_WP = Pose(Vector3(0, 0, 2 * e - overlap), qa), X_WS = Pose(Vector3::Zero(), qb);
  const PairPdAnswer r = Ours(P, X_WP, S, X_WS);
  ASSERT_TRUE(r.in_collision);
  EXPECT_NEAR(r.depth, overlap, 1e-9);
  EXPECT_NEAR((r.normal_W - Vector3::UnitZ()).norm(), 0.0, 1e-6);
}

// Curved primitives against boxes, reference on tessellations.
TEST(GjkEpa, CylinderAndCapsuleAgainstBoxMatchReference) {
  std::mt19937 rng(23);
  const G pairs[][2] = {{Geometry::MakeCylinder(0.08, 0.12), Geometry::MakeBox(Vector3(0.15, 0.1, 0.12))},
                        {Geometry::MakeBox(Vector3(0.15, 0.1, 0.12)), Geometry::MakeCylinder(0.08, 0.12)},
                        {Geometry::MakeCapsule(0.05, 0.1), Geometry::MakeBox(Vector3(0.15, 0.1, 0.12))},
                        {Geometry::MakeCylinder(0.08, 0.12), Geometry::MakeCylinder(0.05, 0.15)},
                        {Geometry::MakeSphere(0.07), Geometry::MakeCylinder(0.08, 0.12)}};
  double worst = 0.0, worst_fcl = 0.0;
  for (const auto& pair : pairs) {
    const double size = pair[0]->radius() + pair[1]->radius();
    for (int i = 0; i < 4; ++i) {
      const Isometry3 X_WS = Pose(Vector3::Zero(), test::RandomRotation(rng));
      Isometry3 X_WP;
      PairPdAnswer r;
      do {
        std::uniform_real_distribution<double> U(-0.2, 0.2);
        X_WP = Pose(Vector3(U(rng), U(rng), U(rng)), test::RandomRotation(rng));
        r = Ours(pair[0], X_WP, pair[1], X_WS);
      } while (!r.in_collision || r.depth < 0.01);
      EXPECT_TRUE(r.converged);
      ExpectFreeAfter(pair[0], X_WP, pair[1], X_WS, r, pair[0]->Describe());
      double tess = 0.0;
      const ReferencePdResult ref =
          test::ReferenceOnTessellations(*pair[0], X_WP, *pair[1], X_WS, 0.02, &tess, 400);
      EXPECT_LE(ref.depth, r.depth + tess + 1e-5 * size) << pair[0]->Describe() << " vs " << pair[1]->Describe();
      EXPECT_GE(ref.depth, r.depth - 1e-5 * size) << pair[0]->Describe() << " vs " << pair[1]->Describe();
      worst = std::max(worst, std::abs(ref.depth - r.depth) / size);
      if (pair[0]->kind() != ShapeKind::kSphere) {
        const double f = FclDepth(*pair[0], X_WP, *pair[1], X_WS, fcl::GST_LIBCCD);
        if (f >= 0) worst_fcl = std::max(worst_fcl, std::abs(f - r.depth) / r.depth);
      }
    }
  }
  std::printf("curved pairs: worst |ours - reference| %.2e of size (2%% tessellations); "
              "worst FCL libccd relative difference from ours %.2e\n", worst, worst_fcl);
}

TEST(GjkEpa, ContainedAndDeep) {
  auto small = Geometry::MakeBox(Vector3(0.05, 0.05, 0.05)), big = Geometry::MakeBox(Vector3(1, 0.8, 0.6));
  PairPdAnswer r = Ours(small, Pose(Vector3(0.1, 0.2, 0.3), Quaternion(0.9, 0.2, 0.1, 0.3)), big,
                        Pose(Vector3::Zero()));
  ASSERT_TRUE(r.in_collision);
  // Exits through +z: 0.6 - 0.3 + the small box's extent along z.
  const Matrix3 R = Quaternion(0.9, 0.2, 0.1, 0.3).normalized().toRotationMatrix();
  const double ext = 0.05 * R.row(2).cwiseAbs().sum();
  EXPECT_NEAR(r.depth, 0.3 + ext, 1e-9);
  EXPECT_NEAR(r.normal_W.z(), 1.0, 1e-6);
  // Scene wholly inside the probe.
  r = Ours(big, Pose(Vector3::Zero()), small, Pose(Vector3(0.9, 0, 0)));
  EXPECT_NEAR(r.depth, 0.15, 1e-9);
  EXPECT_NEAR(r.normal_W.x(), -1.0, 1e-6);
  // Sphere deep in a cylinder: core point inside, margin added.
  r = Ours(Geometry::MakeSphere(0.1), Pose(Vector3(0.05, 0, 0.0)), Geometry::MakeCylinder(0.5, 1.0),
           Pose(Vector3::Zero()));
  EXPECT_NEAR(r.depth, 0.55, 1e-9);
  EXPECT_NEAR(r.normal_W.x(), 1.0, 1e-6);
}

TEST(GjkEpa, DegenerateTouchingAndIdentical) {
  auto box = Geometry::MakeBox(Vector3(0.2, 0.3, 0.4));
  // Exactly touching face to face: free (depth 0).
  PairPdAnswer r = Ours(box, Pose(Vector3(0.4, 0, 0)), box, Pose(Vector3::Zero()));
  EXPECT_FALSE(r.in_collision);
  EXPECT_EQ(r.depth, 0.0);
  // Touching at a corner with rotation.
  // Identical shapes at the same pose: PD = twice the smallest half extent.
  for (const G& g : {G(box), G(Geometry::MakeCylinder(0.1, 0.3)), G(BoxMesh(Vector3(0.2, 0.3, 0.4)))}) {
    const Isometry3 X = Pose(Vector3(1, 2, 3), Quaternion(0.3, 0.4, 0.5, 0.6));
    r = Ours(g, X, g, X);
    ASSERT_TRUE(r.in_collision) << g->Describe();
    EXPECT_NEAR(r.depth, g->kind() == ShapeKind::kCylinder ? 0.2 : 0.4, 1e-9) << g->Describe();
    ExpectFreeAfter(g, X, g, X, r, g->Describe());
  }
  // Barely overlapping (1e-9 of the size).
  r = Ours(box, Pose(Vector3(0.4 - 1e-9, 0, 0)), box, Pose(Vector3::Zero()));
  EXPECT_TRUE(r.in_collision);
  EXPECT_NEAR(r.depth, 1e-9, 1e-12);
}

TEST(GjkEpa, ScaleInvariance) {
  std::mt19937 rng(31);
  const Quaternion qp = test::RandomRotation(rng), qs = test::RandomRotation(rng);
  for (double k : {1e-4, 1.0, 1e3}) {
    auto P = Geometry::MakeCylinder(0.1 * k, 0.2 * k), S = Geometry::MakeBox(k * Vector3(0.2, 0.3, 0.1));
    const PairPdAnswer r = Ours(P, Pose(k * Vector3(0.05, 0.1, 0.12), qp), S, Pose(k * Vector3(0, 0.02, 0), qs));
    ASSERT_TRUE(r.in_collision);
    static double d1 = 0.0;
    if (k == 1e-4) d1 = r.depth / k;
    EXPECT_NEAR(r.depth / k, d1, 1e-8 * d1) << "scale " << k;
  }
}

}  // namespace
}  // namespace pd
