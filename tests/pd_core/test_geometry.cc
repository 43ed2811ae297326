// Geometry: construction checks (bad sizes, convexity of meshes declared
// convex), support points, containment, bounds and surface points.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "pd_core/mesh/convexity_check.h"
#include "pd_core/geometry/geometry.h"
#include "pd_core/geometry/make_shapes.h"
#include "pd_core/geometry/tessellate_geometry.h"
#include "pair_pd_test_helpers.h"

namespace pd {
namespace {

TEST(Geometry, BadSizesThrowNamingFieldAndValue) {
  auto expect_msg = [](auto make, const std::string& needle) {
    try {
      make();
      ADD_FAILURE() << "no throw, expected " << needle;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expect_msg([] { Geometry::MakeSphere(-0.5); }, "radius");
  expect_msg([] { Geometry::MakeSphere(-0.5); }, "-0.5");
  expect_msg([] { Geometry::MakeSphere(std::nan("")); }, "nan");
  expect_msg([] { Geometry::MakeBox(Vector3(1, 0, 1)); }, "half_extents.y");
  expect_msg([] { Geometry::MakeCapsule(0.1, -1.0); }, "half_length");
  expect_msg([] { Geometry::MakeCylinder(0.1, 0.0); }, "cylinder: half_length");
  expect_msg([] { Geometry::MakeCylinder(std::numeric_limits<double>::infinity(), 1.0); },
             "inf");
  EXPECT_NO_THROW(Geometry::MakeCapsule(0.1, 0.0));  // a capsule may be a sphere
  EXPECT_THROW(Geometry::MakeConvexMesh(nullptr), std::invalid_argument);
}

TEST(Geometry, ConvexMeshRefusesCupAndTorusNamingTheViolation) {
  auto cup = CollisionModel::Build(MakeCup(0.04, 0.08, 0.005, 0.006, 24));
  try {
    Geometry::MakeConvexMesh(cup);
    ADD_FAILURE() << "cup accepted as convex";
  } catch (const NotConvexError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("not convex"), std::string::npos) << m;
    EXPECT_NE(m.find("outside the plane of triangle"), std::string::npos) << m;
    EXPECT_NE(m.find("of its bounding radius"), std::string::npos) << m;
  }
  auto torus = CollisionModel::Build(MakeTorus(1.0, 0.3, 24, 12));
  const ConvexityReport rep = CheckConvexity(*torus);
  EXPECT_FALSE(rep.convex);
  // The torus hole: the worst violation is of the order of the tube radius.
  EXPECT_GT(rep.max_violation, 0.2);
  EXPECT_THROW(Geometry::MakeConvexMesh(torus), NotConvexError);
  // Open mesh: refused as not closed.
  TriangleMesh open = MakeBox(Vector3(1, 1, 1));
  open.triangles.pop_back();
  try {
    Geometry::MakeConvexMesh(CollisionModel::Build(open));
    ADD_FAILURE() << "open box accepted";
  } catch (const NotConvexError& e) {
    EXPECT_NE(std::string(e.what()).find("not a closed manifold"), std::string::npos) << e.what();
  }
  // Inside-out box: negative volume.
  TriangleMesh flipped = MakeBox(Vector3(1, 1, 1));
  for (auto& t : flipped.triangles) std::swap(t[1], t[2]);
  EXPECT_THROW(Geometry::MakeConvexMesh(CollisionModel::Build(flipped)), NotConvexError);
}

TEST(Geometry, ConvexMeshAcceptsBoxAndIcosphereAtAnyScale) {
  for (double s : {1e-4, 1.0, 1e3}) {
    EXPECT_NO_THROW(Geometry::MakeConvexMesh(CollisionModel::Build(MakeBox(s * Vector3(1, 2, 3)))));
    EXPECT_NO_THROW(Geometry::MakeConvexMesh(CollisionModel::Build(MakeIcosphere(s, 3))));
  }
}

// Support points agree with brute force over a fine sampling of each shape.
TEST(Geometry, SupportMatchesTessellationAndLiesOnTheShape) {
  const std::vector<std::shared_ptr<const Geometry>> shapes = {
      Geometry::MakeSphere(0.3), Geometry::MakeBox(Vector3(0.1, 0.2, 0.3)),
      Geometry::MakeCapsule(0.1, 0.25), Geometry::MakeCylinder(0.2, 0.15),
      Geometry::MakeConvexMesh(CollisionModel::Build(MakeIcosphere(0.2, 2)))};
  std::mt19937 rng(3);
  std::normal_distribution<double> N;
  for (const auto& g : shapes) {
    const TriangleMesh fine = TessellateGeometry(*g, 1e-4);
    const double err = TessellationError(*g, fine) + 1e-12;
    for (int i = 0; i < 50; ++i) {
      const Vector3 u = Vector3(N(rng), N(rng), N(rng)).normalized();
      const Vector3 s = g->Support(u);
      double brute = -1e300;
      for (const Vector3& v : fine.vertices) brute = std::max(brute, u.dot(v));
      EXPECT_NEAR(u.dot(s), brute, err + 1e-9 * g->radius()) << g->Describe();
      EXPECT_TRUE(g->Contains(s - 1e-9 * g->radius() * u)) << g->Describe();
      EXPECT_FALSE(g->Contains(s + 1e-6 * g->radius() * u)) << g->Describe();
      // Core + margin decomposition.
      EXPECT_NEAR(u.dot(g->CoreSupport(u)) + g->margin(), u.dot(s), 1e-12);
    }
  }
  EXPECT_THROW(Geometry::MakeHalfSpace()->Support(Vector3::UnitZ()), std::logic_error);
}

TEST(Geometry, ContainmentBoundsAndSurfacePoints) {
  auto hs = Geometry::MakeHalfSpace();
  EXPECT_TRUE(hs->Contains(Vector3(5, -3, 0)));
  EXPECT_FALSE(hs->Contains(Vector3(0, 0, 1e-12)));
  EXPECT_FALSE(hs->bounded());
  EXPECT_TRUE(std::isinf(hs->radius()));
  EXPECT_EQ(hs->aabb_max().z(), 0.0);
  EXPECT_TRUE(hs->surface_points().empty());

  auto box = Geometry::MakeBox(Vector3(1, 2, 3));
  EXPECT_TRUE(box->Contains(Vector3(1, 2, 3)));  // boundary counts
  EXPECT_FALSE(box->Contains(Vector3(1.001, 0, 0)));
  EXPECT_EQ(box->surface_points().size(), 26u);
  EXPECT_DOUBLE_EQ(box->radius(), std::sqrt(14.0));

  auto cyl = Geometry::MakeCylinder(0.5, 1.0);
  EXPECT_TRUE(cyl->Contains(Vector3(0.3, 0.4, -1.0)));
  EXPECT_FALSE(cyl->Contains(Vector3(0.3, 0.41, 0)));
  auto cap = Geometry::MakeCapsule(0.5, 1.0);
  EXPECT_TRUE(cap->Contains(Vector3(0, 0, 1.5)));
  EXPECT_FALSE(cap->Contains(Vector3(0.3, 0.3, 1.4)));
  EXPECT_EQ(cap->aabb_max(), Vector3(0.5, 0.5, 1.5));

  // Every surface point of every primitive is on its surface.
  for (const auto& g : {Geometry::MakeSphere(0.3), Geometry::MakeCapsule(0.1, 0.2),
                        Geometry::MakeCylinder(0.2, 0.1), box}) {
    EXPECT_GE(g->surface_points().size(), 20u) << g->Describe();
    for (const Vector3& p : g->surface_points()) {
      const double eps = 1e-9 * g->radius();
      bool inside_near = false, outside_near = false;
      for (int k = 0; k < 6; ++k) {
        const Vector3 q = p + (k % 2 ? -eps : eps) * Vector3::Unit(k / 2);
        (g->Contains(q) ? inside_near : outside_near) = true;
      }
      const bool on_surface = inside_near && outside_near;
      EXPECT_TRUE(on_surface) << g->Describe() << " " << p.transpose();
    }
  }

  auto mesh = Geometry::MakeMesh(CollisionModel::Build(MakeTorus(1.0, 0.3, 24, 12)));
  EXPECT_FALSE(mesh->convex());
  EXPECT_FALSE(mesh->Contains(Vector3::Zero()));  // the hole
  EXPECT_TRUE(mesh->Contains(Vector3(1.0, 0, 0)));
  EXPECT_EQ(mesh->surface_points().size(), mesh->model()->mesh().vertices.size());
  EXPECT_THROW(mesh->sphere(), std::logic_error);
}

// Tessellations circumscribe the primitive within the requested chord error.
TEST(Geometry, TessellationsCircumscribeWithinChordError) {
  for (const auto& g : {Geometry::MakeSphere(0.3), Geometry::MakeCapsule(0.1, 0.2),
                        Geometry::MakeCapsule(0.1, 0.0), Geometry::MakeCylinder(0.2, 0.1)}) {
    for (double e : {3e-3, 2e-2}) {
      const TriangleMesh m = TessellateGeometry(*g, e);
      auto model = CollisionModel::Build(m);
      EXPECT_TRUE(model->closed()) << g->Describe();
      // Faces outside the shape: the mesh contains the primitive.
      for (int t = 0; t < m.num_triangles(); ++t) {
        const Vector3 n = FaceNormal(m, t);
        const double c = n.dot(m.vertices[m.triangles[t][0]]);
        EXPECT_GE(c - n.dot(g->Support(n)), -1e-12 * g->radius()) << g->Describe();
      }
      const double radial = g->kind() == ShapeKind::kCylinder ? g->cylinder().radius
                            : g->kind() == ShapeKind::kSphere ? g->sphere().radius
                                                              : g->capsule().radius;
      EXPECT_LE(TessellationError(*g, m), e * radial * (1 + 1e-9)) << g->Describe();
    }
  }
}

}  // namespace
}  // namespace pd
