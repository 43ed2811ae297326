// The PD dispatcher: method per kind pair, result contract (valid, regions,
// translation), a random sweep of poses for every kind pair with every
// answer verified free, and a reference comparison on a subset.
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <map>
#include <random>

#include "pd_core/convex/convex_pd.h"
#include "pd_core/geometry/make_shapes.h"
#include "pd_core/pair_pd_solver.h"
#include "pair_pd_test_helpers.h"

namespace pd {
namespace {

using test::Pose;
using G = std::shared_ptr<const Geometry>;

// One geometry of every kind, all about 0.1 m across.
std::map<ShapeKind, G> AllKinds() {
  return {{ShapeKind::kHalfSpace, Geometry::MakeHalfSpace()},
          {ShapeKind::kSphere, Geometry::MakeSphere(0.05)},
          {ShapeKind::kBox, Geometry::MakeBox(Vector3(0.06, 0.04, 0.03))},
          {ShapeKind::kCapsule, Geometry::MakeCapsule(0.03, 0.04)},
          {ShapeKind::kCylinder, Geometry::MakeCylinder(0.04, 0.05)},
          {ShapeKind::kConvexMesh,
           Geometry::MakeConvexMesh(CollisionModel::Build(MakeIcosphere(0.05, 1)))},
          {ShapeKind::kMesh, Geometry::MakeMesh(CollisionModel::Build(MakeLRod(0.07, 0.06, 0.03, 0.03)))}};
}

TEST(PairPdSolver, ChoosesTheExpectedMethodForEveryKindPair) {
  using K = ShapeKind;
  const auto kinds = AllKinds();
  const PdMethod C = PdMethod::kClosedForm, E = PdMethod::kConvexGjkEpa, D = PdMethod::kPolyDepth;
  // Rows: probe; columns: scene (HS, sphere, box, capsule, cylinder, convex mesh, mesh).
  const std::map<K, std::array<PdMethod, 7>> table = {
      {K::kSphere, {C, C, C, C, E, E, D}},   {K::kBox, {C, C, E, E, E, E, D}},
      {K::kCapsule, {C, C, E, C, E, E, D}},  {K::kCylinder, {C, E, E, E, E, E, D}},
      {K::kConvexMesh, {C, E, E, E, E, E, D}}, {K::kMesh, {C, D, D, D, D, D, D}}};
  const K order[7] = {K::kHalfSpace, K::kSphere, K::kBox, K::kCapsule, K::kCylinder, K::kConvexMesh, K::kMesh};
  for (const auto& [probe_kind, row] : table)
    for (int j = 0; j < 7; ++j) {
      EXPECT_EQ(ChoosePdMethod(*kinds.at(probe_kind), *kinds.at(order[j])), row[j])
          << ShapeKindName(probe_kind) << " vs " << ShapeKindName(order[j]);
      PairPdSolver solver(kinds.at(probe_kind), kinds.at(order[j]));
      EXPECT_EQ(solver.method(), row[j]);
    }
  try {
    PairPdSolver bad(kinds.at(K::kHalfSpace), kinds.at(K::kBox));
    ADD_FAILURE() << "half-space probe accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("half_space"), std::string::npos) << e.what();
  }
  EXPECT_STREQ(PdMethodName(PdMethod::kConvexGjkEpa), "convex_gjk_epa");
}

// The key fast path: a box (or any mesh) resting into a table plane.
TEST(PairPdSolver, BoxAndToolOnATablePlane) {
  auto table = Geometry::MakeHalfSpace();
  const Isometry3 X_WT = Pose(Vector3(0, 0, 0.7));  // table top at z = 0.7
  PairPdSolver box(Geometry::MakeBox(Vector3(0.1, 0.2, 0.05)), table);
  const Quaternion q(Eigen::AngleAxisd(0.3, Vector3::UnitX()));
  const Isometry3 X_WP = Pose(Vector3(0.3, 0.1, 0.7 + 0.05), q);
  const PenetrationResult r = box.Solve(X_WP, X_WT);
  const double expected = 0.2 * std::sin(0.3) + 0.05 * std::cos(0.3) - 0.05;
  ASSERT_TRUE(r.in_collision);
  EXPECT_TRUE(r.valid);
  EXPECT_NEAR(r.depth, expected, 1e-7 * expected + 1e-12);
  EXPECT_GE(r.depth, expected);  // backed off, never short
  EXPECT_NEAR((r.normal_W - Vector3::UnitZ()).norm(), 0.0, 1e-15);
  ASSERT_EQ(r.num_regions, 1);
  EXPECT_NEAR(r.regions[0].p_W.z(), 0.7 - expected, 1e-12);  // the deepest corner
  EXPECT_NEAR(r.regions[0].local_depth, r.depth, 1e-15);
  EXPECT_GT(r.time_us, 0.0);
  EXPECT_LT(r.iterations, 1);
  // A non-convex tool over the table: closed form too, and exact.
  auto tool = Geometry::MakeMesh(CollisionModel::Build(MakeSpoon(SpoonDimensions{})));
  PairPdSolver spoon(tool, table);
  EXPECT_EQ(spoon.method(), PdMethod::kClosedForm);
  const Isometry3 X_WS = Pose(Vector3(0, 0, 0.7 + 0.001), Quaternion(Eigen::AngleAxisd(0.2, Vector3::UnitY())));
  const PenetrationResult rs = spoon.Solve(X_WS, X_WT);
  double low = 1e300;
  for (const Vector3& v : tool->model()->mesh().vertices) low = std::min(low, (X_WS * v).z());
  ASSERT_TRUE(rs.in_collision);
  EXPECT_NEAR(rs.depth, 0.7 - low, 1e-7 * tool->radius());
  // Lifted clear: free.
  EXPECT_FALSE(box.Solve(TranslatedPose(X_WP, Vector3(0, 0, 0.1)), X_WT).in_collision);
}

// Is the probe, moved by the answer, free of the scene? Convex pairs: GJK
// signed distance; a half-space: every surface/hull point above the plane;
// PolyDepth pairs: the reference collision test on the meshes PolyDepth used
// (the tessellations circumscribe primitives).
bool FreeAfter(const Geometry& P, const Isometry3& X_WP, const Geometry& S, const Isometry3& X_WS,
               const PenetrationResult& r) {
  const Isometry3 moved = TranslatedPose(X_WP, r.translation_W);
  if (!S.bounded()) {
    const Vector3 n = X_WS.linear().col(2);
    const Vector3 low = moved * P.Support(moved.linear().transpose() * -n);
    return n.dot(low - X_WS.translation()) >= 0.0;
  }
  if (P.convex() && S.convex()) return ConvexDistance(P, moved, S, X_WS) >= 0.0;
  const TriangleMesh mp = TessellateGeometry(P, PairPdSolver::kTessellationChordError);
  const TriangleMesh ms = TessellateGeometry(S, PairPdSolver::kTessellationChordError);
  return !ReferenceInCollision(mp, moved, true, ms, X_WS, true);
}

TEST(PairPdSolver, RandomSweepEveryKindPairAllAnswersVerified) {
  const auto kinds = AllKinds();
  std::mt19937 rng(101);
  int total = 0, colliding = 0;
  for (const auto& [pk, P] : kinds) {
    if (!P->bounded()) continue;
    for (const auto& [sk, S] : kinds) {
      PairPdSolver solver(P, S);
      const bool polydepth = solver.method() == PdMethod::kPolyDepth;
      const int poses = polydepth ? 40 : 200;
      int pair_colliding = 0;
      for (int i = 0; i < poses; ++i) {
        const Isometry3 X_WS = Pose(Vector3(0.1, -0.2, 0.3), test::RandomRotation(rng));
        std::uniform_real_distribution<double> U(-1.0, 1.0);
        const double reach = 0.8 * (P->radius() + (S->bounded() ? S->radius() : 0.0));
        const Vector3 offset = S->bounded()
                                   ? Vector3(Vector3(U(rng), U(rng), U(rng)) * reach)
                                   : Vector3(X_WS.linear() * Vector3(U(rng), U(rng), U(rng) * 0.5) * reach);
        const Isometry3 X_WP = Pose(X_WS.translation() + offset, test::RandomRotation(rng));
        const PenetrationResult r = solver.Solve(X_WP, X_WS, /*coherent=*/i % 2 == 1);
        ++total;
        ASSERT_TRUE(std::isfinite(r.depth));
        if (!r.in_collision) {
          EXPECT_EQ(r.depth, 0.0);
          continue;
        }
        ++colliding, ++pair_colliding;
        const std::string label = std::string(ShapeKindName(pk)) + " vs " + ShapeKindName(sk) +
                                  " pose " + std::to_string(i);
        EXPECT_TRUE(r.valid) << label;
        EXPECT_NEAR(r.translation_W.norm(), r.depth, 1e-12 * (1 + r.depth)) << label;
        EXPECT_NEAR(r.normal_W.norm(), 1.0, 1e-9) << label;
        ASSERT_GE(r.num_regions, 1) << label;
        // PolyDepth checks are slow: verify a quarter of them.
        if (!polydepth || i % 4 == 0) {
          EXPECT_TRUE(FreeAfter(*P, X_WP, *S, X_WS, r)) << label << std::setprecision(17)
              << "\nX_WP\n" << X_WP.matrix() << "\nX_WS\n" << X_WS.matrix() << "\ndepth " << r.depth
              << " n " << r.normal_W.transpose() << " it " << r.iterations;
        }
      }
      EXPECT_GT(pair_colliding, poses / 10) << ShapeKindName(pk) << " vs " << ShapeKindName(sk);
    }
  }
  std::printf("sweep: %d queries, %d colliding, all verified\n", total, colliding);
}

// A subset against the slow reference (2% tessellations, error stated per
// case as the sum of both tessellations' errors).
TEST(PairPdSolver, SubsetMatchesReference) {
  const auto kinds = AllKinds();
  std::mt19937 rng(202);
  const std::pair<ShapeKind, ShapeKind> pairs[] = {
      {ShapeKind::kCylinder, ShapeKind::kBox}, {ShapeKind::kConvexMesh, ShapeKind::kCapsule},
      {ShapeKind::kBox, ShapeKind::kHalfSpace}, {ShapeKind::kCapsule, ShapeKind::kCapsule},
      {ShapeKind::kMesh, ShapeKind::kBox}};
  for (const auto& [pk, sk] : pairs) {
    const G P = kinds.at(pk), S = kinds.at(sk);
    PairPdSolver solver(P, S);
    const double size = P->radius() + (S->bounded() ? S->radius() : 0.0);
    int done = 0;
    while (done < 3) {
      const Isometry3 X_WS = Pose(Vector3::Zero(), test::RandomRotation(rng));
      std::uniform_real_distribution<double> U(-0.5, 0.5);
      const Isometry3 X_WP = Pose(Vector3(U(rng), U(rng), U(rng)) * size, test::RandomRotation(rng));
      const PenetrationResult r = solver.Solve(X_WP, X_WS);
      if (!r.in_collision || r.depth < 0.05 * size) continue;
      ++done;
      double tess = 0.0;
      const ReferencePdResult ref = test::ReferenceOnTessellations(*P, X_WP, *S, X_WS, 0.02, &tess);
      const std::string label = std::string(ShapeKindName(pk)) + " vs " + ShapeKindName(sk);
      if (solver.method() != PdMethod::kPolyDepth) {
        EXPECT_NEAR(r.depth, ref.depth, tess + 1e-4 * size) << label;
        continue;
      }
      // PolyDepth (on 1% tessellations) is a verified upper bound that can
      // stop in a local minimum: never shallower than the reference, and
      // within 10% of it on these shapes (measured worst: 5%).
      EXPECT_GE(r.depth, ref.depth - tess - 1e-4 * size) << label;
      EXPECT_LE(r.depth, 1.1 * ref.depth + tess) << label;
    }
  }
}

TEST(PairPdSolver, CoherentQueriesAndReset) {
  auto P = Geometry::MakeCylinder(0.04, 0.05), S = Geometry::MakeBox(Vector3(0.1, 0.1, 0.1));
  PairPdSolver warm(P, S), cold(P, S);
  const Isometry3 X_WS = Pose(Vector3::Zero());
  for (int i = 0; i < 50; ++i) {
    const Isometry3 X_WP = Pose(Vector3(0.001 * i, 0.0005 * i, 0.12 - 0.0004 * i),
                                Quaternion(Eigen::AngleAxisd(0.01 * i, Vector3::UnitX())));
    const PenetrationResult a = warm.Solve(X_WP, X_WS, true), b = cold.Solve(X_WP, X_WS, false);
    ASSERT_EQ(a.in_collision, b.in_collision);
    EXPECT_NEAR(a.depth, b.depth, 1e-8);
  }
  warm.ResetWarmStart();
  EXPECT_EQ(warm.epa_fallbacks(), 0);
  EXPECT_THROW(PairPdSolver(nullptr, S), std::invalid_argument);
}

}  // namespace
}  // namespace pd
