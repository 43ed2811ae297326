// Inner spheres (inner_spheres.h) and the collision certificate on them
// (inner_sphere_overlap.h), with the point distance query they are built on
// (point_clearance.h): distances against a brute force over every triangle;
// every sphere's centre inside by the winding number (solid angles, not the
// ray parity the build uses) and its radius within the brute-force clearance;
// the certificate never fires on a free configuration, fires on most deep
// ones, and the cold search's collision test with it gives InCollision's
// verdict at less work.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>

#include "pd_core/geometry/make_shapes.h"
#include "pd_core/mesh/collision_model.h"
#include "pd_core/mesh/inner_spheres.h"
#include "pd_core/proximity/inner_sphere_overlap.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/point_clearance.h"
#include "pd_core/proximity/point_in_mesh.h"
#include "tests/pd_core/pair_pd_test_helpers.h"
#include "tests/pd_core/point_triangle_distance.h"
#include "tests/pd_core/scaled_mesh_model.h"
#include "tests/prerequisites.h"

namespace pd {
namespace {

using Model = std::shared_ptr<const CollisionModel>;


#define REQUIRE_MESH(file) \
  PD_REQUIRE_FILE(std::string(PD_TEST_MESH_DIR) + "/" + (file), "run scripts/fetch_meshes.sh")

Model Real(const std::string& file) { return test::LoadScaled(file, 1.0); }

TEST(SurfaceDistance, AgreesWithBruteForceAndStopsAtItsCap) {
  REQUIRE_MESH("cow.off");
  Model cow = Real("cow.off");
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  std::uniform_int_distribution<int> pick(0, cow->mesh().num_vertices() - 1);
  for (int i = 0; i < 150; ++i) {
    // Near the surface and well inside or outside it.
    const double spread = (i % 3 == 0 ? 0.3 : 0.02) * cow->radius();
    const Vector3 p = cow->mesh().vertices[pick(rng)] + spread * Vector3(g(rng), g(rng), g(rng));
    const double d = test::BruteForceSurfaceDistance(cow->mesh(), p);
    EXPECT_NEAR(SurfaceDistance(*cow, p, 1e300), d, 1e-12 * cow->radius()) << i;
    // A cap below the distance is returned as is; above it, the distance.
    EXPECT_EQ(SurfaceDistance(*cow, p, 0.5 * d), 0.5 * d) << i;
    EXPECT_NEAR(SurfaceDistance(*cow, p, 2.0 * d), d, 1e-12 * cow->radius()) << i;
  }
}

// Every sphere is a ball inside the solid: centre inside by the winding
// number, no triangle nearer than its radius; they spread (no centre inside
// another sphere); there are some, and no more than asked for.
void ExpectInside(const CollisionModel& m, int max_spheres) {
  const auto& spheres = m.inner_spheres();
  ASSERT_FALSE(spheres.empty()) << m.mesh().name;
  EXPECT_LE(static_cast<int>(spheres.size()), max_spheres) << m.mesh().name;
  for (size_t i = 0; i < spheres.size(); ++i) {
    const InnerSphere& s = spheres[i];
    EXPECT_GT(s.radius, 0.0);
    EXPECT_NEAR(WindingNumber(m, s.p_MC), 1.0, 1e-6) << m.mesh().name << " sphere " << i;
    EXPECT_LT(s.radius, test::BruteForceSurfaceDistance(m.mesh(), s.p_MC))
        << m.mesh().name << " sphere " << i;
    for (size_t j = 0; j < i; ++j)
      EXPECT_GE((s.p_MC - spheres[j].p_MC).norm(), std::max(s.radius, spheres[j].radius));
    if (i > 0) {
      EXPECT_LE(s.radius, spheres[i - 1].radius);  // largest first
    }
  }
}

TEST(InnerSpheres, AreBallsInsideTheSolidOfRealAndProceduralMeshes) {
  for (const char* file : {"cow.off", "knot1.off", "hand.off", "armadillo.off"}) {
    REQUIRE_MESH(file);
    ExpectInside(*Real(file), 32);
  }
  ExpectInside(*CollisionModel::Build(MakeTorus(0.03, 0.01, 24, 12)), 32);
  // A box's biggest ball is about its half width (the lattice's centre cells).
  Model box = CollisionModel::Build(MakeBox(Vector3(0.05, 0.05, 0.05)));
  ExpectInside(*box, 32);
  EXPECT_GT(box->inner_spheres().front().radius, 0.8 * 0.05);
  // Fewer on request.
  EXPECT_EQ(ComputeInnerSpheres(*box, 3).size(), 3u);
}

TEST(InnerSpheres, AnOpenMeshHasNoneAndProvesNothing) {
  TriangleMesh open = MakeBox(Vector3(0.05, 0.05, 0.05));
  open.triangles.pop_back();  // a hole: no solid
  Model m = CollisionModel::Build(open);
  ASSERT_FALSE(m->closed());
  EXPECT_TRUE(m->inner_spheres().empty());
  Model box = CollisionModel::Build(MakeBox(Vector3(0.05, 0.05, 0.05)));
  // Deeply overlapping, either way round: no certificate.
  const Isometry3 X = test::Pose(Vector3(0.01, 0, 0));
  EXPECT_FALSE(InnerSpheresOverlap(ModelPair(*m, *box, X, Isometry3::Identity()), Vector3::Zero()));
  EXPECT_FALSE(InnerSpheresOverlap(ModelPair(*box, *m, X, Isometry3::Identity()), Vector3::Zero()));
}

// Random poses of a real pair from deep overlap to apart: the certificate
// fires only where InCollision (triangle tests and containment) says the
// models collide, fires on most deep configurations, and the collision test
// that asks it first gives InCollision's verdict every time, with less work
// where it fired.
TEST(InnerSphereOverlap, ProvesOnlyCollisionsAndMostDeepOnesOnARealPair) {
  REQUIRE_MESH("cow.off");
  REQUIRE_MESH("hand.off");
  Model cow = Real("cow.off");
  Model hand = Real("hand.off");
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double reach = cow->radius() + hand->radius();
  int colliding = 0, deep = 0, proved = 0, proved_deep = 0;
  int64_t work_plain = 0, work_certified = 0;
  for (int i = 0; i < 400; ++i) {
    const Vector3 d(u(rng), u(rng), u(rng));
    // Distance of the centres: 0 to 0.8 of the reach (the deeper half
    // first: within 0.3 of it the solids overlap by most of their size).
    const double f = (i < 200 ? 0.3 : 0.8) * std::abs(u(rng));
    const Quaternion R_WP = test::RandomRotation(rng);
    // The cow's centre at the hand's, moved along d.
    const Vector3 p_W =
        hand->center() + f * reach * d.normalized() - R_WP.toRotationMatrix() * cow->center();
    const Isometry3 X_WP = test::Pose(p_W, R_WP);
    ProximityCounters plain, certified;
    ModelPair pair(*cow, *hand, X_WP, Isometry3::Identity());
    pair.counters = &plain;
    const bool truth = InCollision(pair, Vector3::Zero());
    pair.counters = &certified;
    const bool with_certificate = InCollisionExpectingDepth(pair, Vector3::Zero());
    pair.counters = nullptr;
    const bool cert = InnerSpheresOverlap(pair, Vector3::Zero());
    EXPECT_EQ(with_certificate, truth) << i;
    if (cert) {
      EXPECT_TRUE(truth) << "certificate on a free configuration, pose " << i;
      ++proved;
      work_plain += plain.total();
      work_certified += certified.total();
    }
    colliding += truth;
    if (i < 200 && truth) {
      ++deep;
      proved_deep += cert;
    }
  }
  EXPECT_GT(colliding, 150);
  EXPECT_LT(colliding, 400);  // some poses are free
  // Most deep configurations are settled by the spheres, at a fraction of
  // the BVH test's work.
  EXPECT_GT(proved_deep, deep / 2) << proved_deep << " of " << deep;
  ASSERT_GT(proved, 0);
  EXPECT_LT(work_certified, work_plain / 2) << work_certified << " vs " << work_plain;
}

// The placed spheres a solver keeps per query (PlacedInnerSpheres) give the
// verdict of a brute force over every sphere pair, written here, and count
// the probe spheres they placed as the unplaced check does; a new pose after
// Invalidate is placed again (a stale placement would give the old pose's
// verdicts).
TEST(InnerSphereOverlap, PlacedSpheresGiveTheBruteForceVerdictAtEachPose) {
  REQUIRE_MESH("cow.off");
  REQUIRE_MESH("hand.off");
  Model cow = Real("cow.off");
  Model hand = Real("hand.off");
  ASSERT_FALSE(cow->inner_spheres().empty());
  ASSERT_FALSE(hand->inner_spheres().empty());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double reach = cow->radius() + hand->radius();
  PlacedInnerSpheres placed;
  int overlapping = 0, apart = 0;
  for (int i = 0; i < 60; ++i) {
    const Quaternion R_WP = test::RandomRotation(rng);
    const Vector3 p_W = hand->center() + 0.5 * reach * Vector3(u(rng), u(rng), u(rng)) -
                        R_WP.toRotationMatrix() * cow->center();
    ModelPair pair(*cow, *hand, test::Pose(p_W, R_WP), Isometry3::Identity());
    placed.Invalidate();
    for (int k = 0; k < 10; ++k) {
      const Vector3 offset_S = 0.3 * reach * Vector3(u(rng), u(rng), u(rng));
      bool truth = false;
      for (const InnerSphere& a : cow->inner_spheres()) {
        const Vector3 p_SA = pair.X_SP.R_SP * a.p_MC + pair.X_SP.p_SP + offset_S;
        for (const InnerSphere& b : hand->inner_spheres())
          truth |= (p_SA - b.p_MC).norm() < a.radius + b.radius;
      }
      ProximityCounters unplaced_count, placed_count;
      pair.inner_spheres = nullptr;
      pair.counters = &unplaced_count;
      const bool unplaced = InnerSpheresOverlap(pair, offset_S);
      pair.inner_spheres = &placed;
      pair.counters = &placed_count;
      EXPECT_EQ(InnerSpheresOverlap(pair, offset_S), truth) << "pose " << i << " offset " << k;
      EXPECT_EQ(unplaced, truth) << "pose " << i << " offset " << k;
      EXPECT_EQ(placed_count.box_tests, unplaced_count.box_tests) << i << " " << k;
      (truth ? overlapping : apart) += 1;
    }
  }
  // Both verdicts were exercised.
  EXPECT_GT(overlapping, 60);
  EXPECT_GT(apart, 60);
}

}  // namespace
}  // namespace pd
