// Containment (issue 12): point in a closed mesh exact and failing closed,
// the ray traversal's bounded stack, one vertex per connected component, and
// multi-part meshes wholly inside the other solid in both directions, checked
// against analytic answers and the independent reference collision test.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "pd_core/mesh/load_mesh.h"
#include "pd_core/geometry/make_shapes.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/point_in_mesh.h"
#include "pd_core/polydepth/polydepth.h"
#include "pd_core/reference/reference_pd.h"
#include "tests/prerequisites.h"

namespace pd {
namespace {

using Model = std::shared_ptr<const CollisionModel>;

// The mesh: two cubes of half-size 0.01, the far one (x = 0.1)
// listed first, the other at the origin.
TriangleMesh TwoCubes() {
  const TriangleMesh cube = MakeBox(Vector3::Constant(0.01));
  return JoinedMeshes(TranslatedMesh(cube, Vector3(0.1, 0, 0)), cube);
}

Isometry3 At(const Vector3& p, const Quaternion& q = Quaternion::Identity()) {
  return MakePose(p, q.w(), q.x(), q.y(), q.z());
}

TEST(PointInMesh, BoundaryOfAClosedMeshIsInsideAndNearbyPointsAreExact) {
  // Every ray cast from a vertex or an edge grazes: the answer must fail
  // closed (the solid includes its boundary), never open.
  Model box = CollisionModel::Build(MakeBox(Vector3(0.3, 0.2, 0.1)));
  for (const Vector3& v : box->mesh().vertices) {
    EXPECT_TRUE(PointInsideMesh(*box, v)) << v.transpose();
    EXPECT_TRUE(PointInsideMesh(*box, v * (1 - 1e-9))) << v.transpose();
  }
  for (const auto& e : box->topology().edges) {
    const Vector3 mid = 0.5 * (box->mesh().vertices[e.v0] + box->mesh().vertices[e.v1]);
    EXPECT_TRUE(PointInsideMesh(*box, mid)) << "edge midpoint " << mid.transpose();
  }
  const Vector3 h(0.3, 0.2, 0.1);
  for (int k = 0; k < 3; ++k) {
    for (double sign : {-1.0, 1.0}) {
      const Vector3 face = sign * h[k] * Vector3::Unit(k);
      EXPECT_TRUE(PointInsideMesh(*box, face)) << "face centre " << face.transpose();
      EXPECT_TRUE(PointInsideMesh(*box, face * (1 - 1e-9)));
      EXPECT_FALSE(PointInsideMesh(*box, face * (1 + 1e-9)));
    }
  }
}

// Ray parity against the exact winding number (sum of solid angles, no BVH)
// at random points around a non-convex closed mesh.
TEST(PointInMesh, AgreesWithTheExactWindingNumberOnANonConvexMesh) {
  Model knot = CollisionModel::Build(MakeTorusKnot(2, 3, 0.2, 1.0, 96, 8));
  ASSERT_TRUE(knot->closed());
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> U(-1.4, 1.4);
  int inside = 0;
  for (int i = 0; i < 1500; ++i) {
    const Vector3 p(U(rng), U(rng), 0.4 * U(rng));
    const double w = WindingNumber(*knot, p);
    ASSERT_NEAR(w, std::round(w), 1e-6) << p.transpose();
    const bool in = PointInsideMesh(*knot, p);
    EXPECT_EQ(in, std::abs(w) > 0.5) << p.transpose() << " winding " << w;
    inside += in;
  }
  EXPECT_GT(inside, 50);  // the test sees both answers
}

// The traversal keeps a fixed, checked stack: with room for fewer pending
// nodes than the BVH is deep, the overflowing subtrees are scanned directly
// and every count is the same as with the full stack.
TEST(PointInMesh, RayTraversalStackBoundHoldsForAnyDepth) {
  Model ball = CollisionModel::Build(MakeIcosphere(0.5, 4));
  const int depth = ball->bvh().depth();
  ASSERT_GT(depth, 8);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-0.6, 0.6);
  std::normal_distribution<double> G;
  int clean = 0, crossed = 0;
  for (int i = 0; i < 300; ++i) {
    const Vector3 p(U(rng), U(rng), U(rng));
    const Vector3 d = Vector3(G(rng), G(rng), G(rng)).normalized();
    const RayCrossings full = CountRayCrossings(*ball, p, d);
    for (int capacity : {0, 1, 2, 3, depth / 2, depth - 1, 1000}) {
      const RayCrossings bounded = CountRayCrossings(*ball, p, d, capacity);
      ASSERT_EQ(bounded.status, full.status) << "capacity " << capacity;
      ASSERT_EQ(bounded.crossings, full.crossings) << "capacity " << capacity;
    }
    if (full.status == RayCount::kClean) {
      ++clean;
      crossed += full.crossings > 0;
      // A ray from inside the convex ball crosses once, from outside 0 or 2
      // (its faces lie between radius 0.499 and 0.5).
      if (std::abs(p.norm() - 0.4995) > 0.0005)
        EXPECT_EQ(full.crossings % 2 == 1, p.norm() < 0.499) << p.transpose();
    }
  }
  EXPECT_GT(clean, 290);
  EXPECT_GT(crossed, 100);
}

TEST(CollisionModel, OneVertexPerConnectedComponent) {
  EXPECT_EQ(CollisionModel::Build(MakeBox(Vector3::Constant(1)))->component_vertices(), std::vector<int>{0});
  Model two = CollisionModel::Build(TwoCubes());
  EXPECT_EQ(two->component_vertices(), (std::vector<int>{0, 8}));
  // Three parts, the last touching nothing, plus an unused vertex.
  TriangleMesh three = JoinedMeshes(TwoCubes(), TranslatedMesh(MakeIcosphere(0.01, 1), Vector3(0, 0.1, 0)));
  three.vertices.push_back(Vector3(5, 5, 5));
  EXPECT_EQ(CollisionModel::Build(three)->component_vertices(), (std::vector<int>{0, 8, 16}));
}

// The case: a part of a two-part mesh wholly inside a cube of
// half-size 0.025, no surface crossing; either mesh as the probe. Exact PD:
// the small cube leaves along any axis by 0.025 + 0.01 = 0.035 (the far part
// stays clear of the cube moving either way).
TEST(MultiPartContainment, PartWhollyInsideTheOtherSolidCollidesEitherWay) {
  Model parts = CollisionModel::Build(TwoCubes());
  Model cube = CollisionModel::Build(MakeBox(Vector3::Constant(0.025)));
  ASSERT_TRUE(parts->closed() && cube->closed());
  const Isometry3 I = Isometry3::Identity();
  for (bool parts_probe : {true, false}) {
    const Model& P = parts_probe ? parts : cube;
    const Model& S = parts_probe ? cube : parts;
    const std::string label = parts_probe ? "two cubes as probe" : "two cubes as scene";
    // Independent collision test first: the case is a collision.
    ASSERT_TRUE(ReferenceInCollision(P->mesh(), I, true, S->mesh(), I, true)) << label;
    const ModelPair pair(*P, *S, I, I);
    EXPECT_FALSE(SurfacesIntersect(pair, Vector3::Zero())) << label;
    EXPECT_TRUE(InCollision(pair, Vector3::Zero())) << label;
    PolyDepthSolver solver(P, S);
    const PenetrationResult r = solver.Solve(I, I);
    ASSERT_TRUE(r.in_collision) << label;
    EXPECT_TRUE(r.valid) << label;
    EXPECT_NEAR(r.depth, 0.035, 1e-6 * 0.035) << label;
    EXPECT_GT(r.normal_W.cwiseAbs().maxCoeff(), 1 - 1e-9) << label << ": " << r.normal_W.transpose();
    EXPECT_FALSE(ReferenceInCollision(P->mesh(), I, true, S->mesh(), I, true, r.translation_W))
        << label << ": the answer is not free";
  }
}

// Random poses of a three-part probe around a non-convex closed scene: the
// collision test agrees with the independent reference everywhere, and
// parts wholly inside the scene (no surface crossing) occur.
TEST(MultiPartContainment, AgreesWithTheReferenceAtRandomPoses) {
  const TriangleMesh part = MakeBox(Vector3(0.04, 0.03, 0.02));
  const TriangleMesh probe = JoinedMeshes(JoinedMeshes(TranslatedMesh(part, Vector3(0.6, 0, 0)), part),
                                          TranslatedMesh(MakeIcosphere(0.03, 1), Vector3(0, 0.5, 0.1)));
  Model P = CollisionModel::Build(probe);
  Model S = CollisionModel::Build(MakeTorus(0.6, 0.25, 48, 24));
  ASSERT_EQ(P->component_vertices().size(), 3u);
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int contained_only = 0, colliding = 0;
  for (int i = 0; i < 300; ++i) {
    const Isometry3 X_WP = At(Vector3(U(rng), U(rng), 0.2 * U(rng)) * 0.9,
                              Quaternion(U(rng), U(rng), U(rng), U(rng)).normalized());
    const Isometry3 X_WS = At(Vector3::Zero());
    const ModelPair pair(*P, *S, X_WP, X_WS);
    const bool fast = InCollision(pair, Vector3::Zero());
    ASSERT_EQ(fast, ReferenceInCollision(P->mesh(), X_WP, true, S->mesh(), X_WS, true)) << "pose " << i;
    colliding += fast;
    contained_only += fast && !SurfacesIntersect(pair, Vector3::Zero());
  }
  EXPECT_GT(colliding, 30);
  EXPECT_GT(contained_only, 5);
}

// CGAL's bones.off (many closed parts). For each bone k: a two-part mesh of
// another bone j that lies clear of k (listed first) and bone k, against a
// box that swallows bone k whole; either mesh as the probe.
TEST(MultiPartContainment, EachBoneOfCgalBonesInsideABox) {
  const std::string path = std::string(PD_TEST_MESH_DIR) + "/bones.off";
  PD_REQUIRE_FILE(path, "run scripts/fetch_meshes.sh");
  Model bones = CollisionModel::Build(LoadMesh(path).mesh);
  ASSERT_TRUE(bones->closed()) << bones->topology().Describe();
  const int parts = static_cast<int>(bones->component_vertices().size());
  EXPECT_GT(parts, 20);
  // Each bone as a mesh of its own: label vertices by the representative
  // they connect to, then copy each part's triangles.
  const TriangleMesh& all = bones->mesh();
  std::vector<int> part_of(all.num_vertices(), -1);
  for (int k = 0; k < parts; ++k) part_of[bones->component_vertices()[k]] = k;
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& t : all.triangles) {
      int k = -1;
      for (int j = 0; j < 3; ++j) k = std::max(k, part_of[t[j]]);
      for (int j = 0; j < 3; ++j)
        if (k >= 0 && part_of[t[j]] != k) part_of[t[j]] = k, changed = true;
    }
  }
  std::vector<TriangleMesh> bone(parts);
  std::vector<int> index(all.num_vertices(), -1);
  for (int v = 0; v < all.num_vertices(); ++v) {
    if (part_of[v] < 0) continue;
    index[v] = bone[part_of[v]].num_vertices();
    bone[part_of[v]].vertices.push_back(all.vertices[v]);
  }
  for (const auto& t : all.triangles)
    bone[part_of[t[0]]].triangles.emplace_back(index[t[0]], index[t[1]], index[t[2]]);
  const Isometry3 I = Isometry3::Identity();
  int checked = 0;
  for (int k = 0; k < parts; ++k) {
    const MeshBounds b = ComputeBounds(bone[k]);
    const Vector3 half = 0.5 * (b.max - b.min) + Vector3::Constant(1e-3 * b.diagonal());
    Model box = CollisionModel::Build(TranslatedMesh(MakeBox(half), b.center()));
    // The first other bone whose bounds stay clear of the box.
    for (int j = 0; j < parts; ++j) {
      const MeshBounds bj = ComputeBounds(bone[j]);
      const bool overlap = (bj.max.array() > b.center().array() - half.array()).all() &&
                           (bj.min.array() < b.center().array() + half.array()).all();
      if (j == k || overlap) continue;
      Model pair_of_bones = CollisionModel::Build(JoinedMeshes(bone[j], bone[k]));
      ASSERT_EQ(pair_of_bones->component_vertices().size(), 2u);
      for (bool bones_probe : {true, false}) {
        const ModelPair pair =
            bones_probe ? ModelPair(*pair_of_bones, *box, I, I) : ModelPair(*box, *pair_of_bones, I, I);
        ASSERT_FALSE(SurfacesIntersect(pair, Vector3::Zero())) << "bones " << j << ", " << k;
        EXPECT_TRUE(InCollision(pair, Vector3::Zero())) << "bones " << j << ", " << k;
      }
      ++checked;
      break;
    }
  }
  EXPECT_GT(checked, parts / 2);
  std::printf("[ bones    ] %d parts, %d checked in both roles\n", parts, checked);
}

}  // namespace
}  // namespace pd
