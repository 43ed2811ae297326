#include "pd_core/geometry/make_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <utility>

#include "pd_core/mesh/mesh_topology.h"
#include "pd_core/proximity/triangle_geometry.h"
#include "tests/mesh_checks.h"

namespace pd {
namespace {

using test::ConsistentlyOriented;
using test::SignedVolume;

// Every check a generated solid must pass.
void ExpectClosedOutward(const TriangleMesh& mesh) {
  const MeshTopology topo = ComputeTopology(mesh);
  EXPECT_TRUE(topo.closed()) << mesh.name << ": " << topo.Describe();
  EXPECT_EQ(topo.num_degenerate_triangles, 0) << mesh.name;
  EXPECT_TRUE(ConsistentlyOriented(mesh)) << mesh.name;
  EXPECT_GT(SignedVolume(mesh), 0.0) << mesh.name;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_GE(t[k], 0);
      ASSERT_LT(t[k], mesh.num_vertices());
    }
  }
  // Euler characteristic V - E + F of a closed orientable surface is even.
  const int euler = mesh.num_vertices() - static_cast<int>(topo.edges.size()) + mesh.num_triangles();
  EXPECT_EQ(euler % 2, 0) << mesh.name;
}

int EulerCharacteristic(const TriangleMesh& mesh) {
  return mesh.num_vertices() - static_cast<int>(ComputeTopology(mesh).edges.size()) +
         mesh.num_triangles();
}

// Distance along the ray origin + s * dir (s >= 0) to the first triangle hit.
std::optional<double> FirstHit(const TriangleMesh& mesh, const Vector3& origin, const Vector3& dir) {
  std::optional<double> best;
  for (const auto& t : mesh.triangles) {
    const Vector3& a = mesh.vertices[t[0]];
    const Vector3 e1 = mesh.vertices[t[1]] - a, e2 = mesh.vertices[t[2]] - a;
    const Vector3 p = dir.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-15) continue;
    const Vector3 s = origin - a;
    const double u = s.dot(p) / det;
    const Vector3 q = s.cross(e1);
    const double v = dir.dot(q) / det;
    const double dist = e2.dot(q) / det;
    if (u < 0 || v < 0 || u + v > 1 || dist < 0) continue;
    if (!best || dist < *best) best = dist;
  }
  return best;
}

TEST(MakeShapes, BoxIsExact) {
  const Vector3 h(0.1, 0.2, 0.3);
  const TriangleMesh box = MakeBox(h);
  EXPECT_EQ(box.num_triangles(), 12);
  EXPECT_EQ(box.num_vertices(), 8);
  ExpectClosedOutward(box);
  EXPECT_NEAR(SignedVolume(box), 8 * h.prod(), 1e-15);
  const MeshBounds b = ComputeBounds(box);
  EXPECT_TRUE(b.min.isApprox(-h));
  EXPECT_TRUE(b.max.isApprox(h));
  EXPECT_EQ(EulerCharacteristic(box), 2);
}

TEST(MakeShapes, IcosphereCountsRadiusAndVolume) {
  const double r = 0.05;
  for (int s = 0; s <= 3; ++s) {
    const TriangleMesh sphere = MakeIcosphere(r, s);
    const int four_s = 1 << (2 * s);
    EXPECT_EQ(sphere.num_triangles(), 20 * four_s);
    EXPECT_EQ(sphere.num_vertices(), 10 * four_s + 2);
    ExpectClosedOutward(sphere);
    EXPECT_EQ(EulerCharacteristic(sphere), 2);
    for (const Vector3& v : sphere.vertices) EXPECT_NEAR(v.norm(), r, 1e-15);
    // Inscribed polyhedron: below the sphere's volume, approaching it.
    const double ball = 4.0 / 3.0 * M_PI * r * r * r;
    EXPECT_LT(SignedVolume(sphere), ball);
    if (s == 3) {
      EXPECT_GT(SignedVolume(sphere), 0.98 * ball);
    }
  }
}

TEST(MakeShapes, CylinderMatchesPrismVolume) {
  const double r = 0.02, length = 0.1;
  const int n = 32;
  const TriangleMesh cyl = MakeCylinder(r, length, n);
  EXPECT_EQ(cyl.num_triangles(), 4 * n);
  ExpectClosedOutward(cyl);
  // Regular n-gon prism.
  EXPECT_NEAR(SignedVolume(cyl), 0.5 * n * r * r * std::sin(2 * M_PI / n) * length, 1e-15);
  const MeshBounds b = ComputeBounds(cyl);
  EXPECT_NEAR(b.min.z(), -0.05, 1e-15);
  EXPECT_NEAR(b.max.z(), 0.05, 1e-15);
  EXPECT_NEAR(b.max.x(), r, 1e-15);
}

TEST(MakeShapes, TorusIsGenusOne) {
  const double R = 0.1, r = 0.03;
  const TriangleMesh torus = MakeTorus(R, r, 48, 24);
  EXPECT_EQ(torus.num_triangles(), 2 * 48 * 24);
  ExpectClosedOutward(torus);
  EXPECT_EQ(EulerCharacteristic(torus), 0);
  const double exact = 2 * M_PI * M_PI * R * r * r;
  EXPECT_NEAR(SignedVolume(torus), exact, 0.02 * exact);
  // The hole: a ray down the z axis passes through without hitting anything.
  EXPECT_FALSE(FirstHit(torus, Vector3(0, 0, 1), -Vector3::UnitZ()).has_value());
}

TEST(MakeShapes, TorusKnotIsAClosedTubeThatDoesNotCrossItself) {
  const double tube = 0.1, scale = 1.0;
  const TriangleMesh knot = MakeTorusKnot(2, 3, tube, scale);
  EXPECT_EQ(knot.num_triangles(), 2 * 256 * 6);
  ExpectClosedOutward(knot);
  EXPECT_EQ(EulerCharacteristic(knot), 0);  // a knotted torus
  // Tube volume ~ hexagon area times length; the hexagon has 3 sqrt(3)/2 r^2.
  const double hexagon = 1.5 * std::sqrt(3.0) * tube * tube;
  const double volume = SignedVolume(knot);
  EXPECT_GT(volume, 0.9 * hexagon * 2 * M_PI * 2 * scale * 0.5);  // length > 2 turns of r = 0.5
  // The tube stays within the torus it winds around, thickened by the tube.
  for (const Vector3& v : knot.vertices) {
    const double rho = std::hypot(v.x(), v.y());
    EXPECT_LE(std::hypot(rho - scale, v.z()), 0.5 * scale + tube + 1e-12);
  }
  // No two triangles that share no vertex intersect.
  std::vector<Vector3> lo(knot.num_triangles()), hi(knot.num_triangles());
  for (int t = 0; t < knot.num_triangles(); ++t) {
    const auto& f = knot.triangles[t];
    lo[t] = knot.vertices[f[0]].cwiseMin(knot.vertices[f[1]]).cwiseMin(knot.vertices[f[2]]);
    hi[t] = knot.vertices[f[0]].cwiseMax(knot.vertices[f[1]]).cwiseMax(knot.vertices[f[2]]);
  }
  int crossings = 0;
  for (int a = 0; a < knot.num_triangles(); ++a) {
    for (int b = a + 1; b < knot.num_triangles(); ++b) {
      if ((lo[a].array() > hi[b].array()).any() || (lo[b].array() > hi[a].array()).any()) continue;
      const auto& fa = knot.triangles[a];
      const auto& fb = knot.triangles[b];
      bool share = false;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) share |= fa[i] == fb[j];
      if (share) continue;
      crossings += TrianglesIntersect(knot.vertices[fa[0]], knot.vertices[fa[1]],
                                      knot.vertices[fa[2]], knot.vertices[fb[0]],
                                      knot.vertices[fb[1]], knot.vertices[fb[2]]);
    }
  }
  EXPECT_EQ(crossings, 0);
}

TEST(MakeShapes, TorusKnotRefusesSelfIntersectingOrLinkedInput) {
  EXPECT_THROW(MakeTorusKnot(2, 3, 0.45, 1.0), std::invalid_argument);  // tube too thick
  EXPECT_THROW(MakeTorusKnot(2, 4, 0.05, 1.0), std::invalid_argument);  // not coprime
  EXPECT_THROW(MakeTorusKnot(2, 3, 0.05, 1.0, 2, 6), std::invalid_argument);
  EXPECT_NO_THROW(MakeTorusKnot(3, 2, 0.05, 1.0));
}

TEST(MakeShapes, USlotHasTheSlotCutOut) {
  const Vector3 h(0.1, 0.05, 0.04);
  const double width = 0.02, depth = 0.05;
  const TriangleMesh slot = MakeUSlot(h, width, depth);
  EXPECT_EQ(slot.num_triangles(), 28);
  ExpectClosedOutward(slot);
  EXPECT_EQ(EulerCharacteristic(slot), 2);
  EXPECT_NEAR(SignedVolume(slot), 2 * h.x() * (4 * h.y() * h.z() - width * depth), 1e-15);
  const MeshBounds b = ComputeBounds(slot);
  EXPECT_TRUE(b.min.isApprox(-h));
  EXPECT_TRUE(b.max.isApprox(h));
  // Looking down: the slot floor at the centre, the top face beside the slot.
  const Vector3 down = -Vector3::UnitZ();
  for (double x : {-0.09, 0.0, 0.09}) {
    auto centre = FirstHit(slot, Vector3(x, 0.0, 1.0), down);
    ASSERT_TRUE(centre.has_value());
    EXPECT_NEAR(1.0 - *centre, h.z() - depth, 1e-12);
    auto side = FirstHit(slot, Vector3(x, 0.03, 1.0), down);
    ASSERT_TRUE(side.has_value());
    EXPECT_NEAR(1.0 - *side, h.z(), 1e-12);
  }
  // Looking along x through the slot: open end to end.
  EXPECT_FALSE(FirstHit(slot, Vector3(1.0, 0.0, 0.03), -Vector3::UnitX()).has_value());
  // Sideways from inside the slot: a wall at y = width / 2.
  auto wall = FirstHit(slot, Vector3(0.0, 0.0, 0.0), Vector3::UnitY());
  ASSERT_TRUE(wall.has_value());
  EXPECT_NEAR(*wall, 0.5 * width, 1e-12);
}

TEST(MakeShapes, USlotRefusesSlotsThatSplitTheBox) {
  EXPECT_THROW(MakeUSlot(Vector3(0.1, 0.05, 0.04), 0.1, 0.02), std::invalid_argument);
  EXPECT_THROW(MakeUSlot(Vector3(0.1, 0.05, 0.04), 0.02, 0.08), std::invalid_argument);
  EXPECT_THROW(MakeUSlot(Vector3(0.1, 0.05, 0.04), 0.0, 0.02), std::invalid_argument);
}

TEST(MakeShapes, ThinPlate) {
  const TriangleMesh plate = MakeThinPlate(0.2, 0.1, 0.001);
  EXPECT_EQ(plate.num_triangles(), 12);
  ExpectClosedOutward(plate);
  EXPECT_NEAR(SignedVolume(plate), 8 * 0.2 * 0.1 * 0.001, 1e-15);
  EXPECT_NEAR(ComputeBounds(plate).max.z(), 0.001, 1e-15);
}

TEST(MakeShapes, RejectsInvalidSizes) {
  EXPECT_THROW(MakeBox(Vector3(0.1, 0.0, 0.1)), std::invalid_argument);
  EXPECT_THROW(MakeBox(Vector3(0.1, std::nan(""), 0.1)), std::invalid_argument);
  EXPECT_THROW(MakeIcosphere(-1.0, 2), std::invalid_argument);
  EXPECT_THROW(MakeIcosphere(1.0, 9), std::invalid_argument);
  EXPECT_THROW(MakeCylinder(0.1, 0.1, 2), std::invalid_argument);
  EXPECT_THROW(MakeTorus(0.1, 0.2, 16, 8), std::invalid_argument);
  EXPECT_THROW(MakeThinPlate(0.1, 0.1, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace pd
