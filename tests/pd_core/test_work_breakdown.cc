// Where a PolyDepth query's work goes (PenetrationResult::work, booked by
// WorkScope in the proximity queries): the parts sum to the query's box and
// triangle tests, each query kind lands in its own part, and a free query's
// work is the collision test's own, counted by calling it directly.
#include <gtest/gtest.h>

#include <memory>

#include "pd_core/geometry/make_shapes.h"
#include "pd_core/polydepth/polydepth.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"
#include "pd_core/proximity/translational_ccd.h"

namespace pd {
namespace {

using Model = std::shared_ptr<const CollisionModel>;

Isometry3 At(const Vector3& p) {
  Isometry3 X = Isometry3::Identity();
  X.translation() = p;
  return X;
}

int64_t Sum(const PenetrationResult::Work& w) {
  return w.collision + w.localisation + w.out_projection + w.list_builds + w.other;
}

TEST(WorkScope, BooksTheOutermostQueryKindOnly) {
  ProximityCounters c;
  {
    WorkScope outer(&c, QueryKind::kCollision);
    c.box_tests += 5;
    {
      WorkScope inner(&c, QueryKind::kLocalisation);  // inside a collision test
      c.triangle_tests += 3;
    }
  }
  {
    WorkScope ccd(&c, QueryKind::kOutProjection);
    c.box_tests += 7;
  }
  c.box_tests += 2;  // outside any scope
  EXPECT_EQ(c.by_kind[static_cast<int>(QueryKind::kCollision)], 8);
  EXPECT_EQ(c.by_kind[static_cast<int>(QueryKind::kLocalisation)], 0);
  EXPECT_EQ(c.by_kind[static_cast<int>(QueryKind::kOutProjection)], 7);
  EXPECT_EQ(c.total(), 17);
  EXPECT_EQ(c.open_scopes, 0);
}

TEST(WorkScope, ProximityQueriesBookTheirOwnKind) {
  Model P = CollisionModel::Build(MakeIcosphere(0.01, 3));
  Model S = CollisionModel::Build(MakeIcosphere(0.1, 4));
  ModelPair pair(*P, *S, At(Vector3(0.0, 0.0, 0.105)), Isometry3::Identity());
  ProximityCounters c;
  pair.counters = &c;
  ASSERT_TRUE(InCollision(pair, Vector3::Zero()));
  const int64_t after_collision = c.total();
  EXPECT_GT(after_collision, 0);
  EXPECT_EQ(c.by_kind[static_cast<int>(QueryKind::kCollision)], after_collision);
  // Out along +z from a free start: the CCD's work is out-projection work.
  EXPECT_GE(FirstContactAlongTranslation(pair, Vector3(0.0, 0.0, 0.05), Vector3(0.0, 0.0, -0.05)),
            0.0);
  EXPECT_EQ(c.by_kind[static_cast<int>(QueryKind::kOutProjection)], c.total() - after_collision);
  EXPECT_GT(c.total(), after_collision);
}

// A free query, a cold colliding query and a warm slide over a sphere.
TEST(PolyDepth, WorkBreakdownSumsToTheQueryWorkByKind) {
  const double R = 0.1, r = 0.01;
  Model P = CollisionModel::Build(MakeIcosphere(r, 3));
  Model S = CollisionModel::Build(MakeIcosphere(R, 5));
  const Isometry3 X_WS = Isometry3::Identity();
  const double size = R + r;

  // Free: the query's collision test is all it does; the same test made
  // directly counts the same work.
  {
    PolyDepthSolver solver(P, S);
    const Isometry3 X_WP = At(Vector3(0.0, 0.0, R + r + 0.01));
    const PenetrationResult res = solver.Solve(X_WP, X_WS);
    ASSERT_FALSE(res.in_collision);
    ProximityCounters direct;
    ModelPair pair(*P, *S, X_WP, X_WS);
    pair.counters = &direct;
    ASSERT_FALSE(InCollision(pair, Vector3::Zero()));
    EXPECT_EQ(res.work.collision, direct.total());
    EXPECT_EQ(Sum(res.work), res.box_tests + res.triangle_tests);
    EXPECT_EQ(res.work.localisation + res.work.out_projection + res.work.list_builds, 0);
  }
  // Cold and colliding: starts out-project, iterations localise; no list.
  {
    PolyDepthSolver solver(P, S);
    const PenetrationResult res = solver.Solve(At(Vector3(0.0, 0.0, R + 0.5 * r)), X_WS);
    ASSERT_TRUE(res.in_collision);
    ASSERT_TRUE(res.valid);
    EXPECT_EQ(Sum(res.work), res.box_tests + res.triangle_tests);
    EXPECT_GT(res.work.collision, 0);
    EXPECT_GT(res.work.localisation, 0);
    EXPECT_GT(res.work.out_projection, 0);
    EXPECT_EQ(res.work.list_builds, 0);
    EXPECT_GE(res.work.other, 0);
  }
  // Warm slide along a great circle, 1e-3 of the size per query, pressed in
  // by 1e-3 of it: list work exactly on the queries that built a list.
  {
    PolyDepthSolver solver(P, S);
    int with_builds = 0;
    for (int i = 0; i < 40; ++i) {
      const double theta = i * 1e-3 * size / R;
      const double rho = R + r - 1e-3 * size;
      const PenetrationResult res =
          solver.Solve(At(rho * Vector3(std::sin(theta), 0.0, std::cos(theta))), X_WS, true);
      ASSERT_TRUE(res.in_collision) << "pose " << i;
      EXPECT_EQ(Sum(res.work), res.box_tests + res.triangle_tests) << "pose " << i;
      EXPECT_EQ(res.work.list_builds > 0, res.list_builds > 0) << "pose " << i;
      with_builds += res.list_builds > 0;
    }
    EXPECT_GT(with_builds, 0);
  }
}

}  // namespace
}  // namespace pd
