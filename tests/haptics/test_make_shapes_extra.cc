// The shapes added to pd_core/make_shapes for the haptic scenes: closed,
// consistently oriented outward, right size and topology.
#include <gtest/gtest.h>

#include <map>
#include <stdexcept>

#include "pd_core/geometry/make_shapes.h"
#include "pd_core/mesh/mesh_topology.h"
#include "tests/mesh_checks.h"

namespace pd {
namespace {

using test::ConsistentlyOriented;
using test::SignedVolume;

// Closed, oriented, positive volume, no degenerate triangle; returns the
// genus from the Euler characteristic V - E + F = 2 - 2g.
int ExpectSolid(const TriangleMesh& mesh) {
  const MeshTopology topo = ComputeTopology(mesh);
  EXPECT_TRUE(topo.closed()) << mesh.name << ": " << topo.Describe();
  EXPECT_EQ(topo.num_degenerate_triangles, 0) << mesh.name;
  EXPECT_TRUE(ConsistentlyOriented(mesh)) << mesh.name;
  EXPECT_GT(SignedVolume(mesh), 0.0) << mesh.name;
  const int euler = mesh.num_vertices() - static_cast<int>(topo.edges.size()) + mesh.num_triangles();
  return (2 - euler) / 2;
}

TEST(MakeCup, ClosedGenusZeroWithTheRightVolume) {
  const double R = 0.035, H = 0.06, wall = 0.008, floor = 0.01;
  const int n = 64;
  const TriangleMesh cup = MakeCup(R, H, wall, floor, n);
  EXPECT_EQ(ExpectSolid(cup), 0);
  EXPECT_EQ(cup.num_triangles(), 8 * n - 4);
  EXPECT_EQ(cup.num_vertices(), 4 * n);
  // Polygon areas: n/2 r^2 sin(2 pi / n).
  const double k = 0.5 * n * std::sin(2.0 * M_PI / n);
  const double r = R - wall;
  const double expected = k * R * R * H - k * r * r * (H - floor);
  EXPECT_NEAR(SignedVolume(cup), expected, 1e-12);
  const MeshBounds b = ComputeBounds(cup);
  EXPECT_NEAR(b.min.z(), -H / 2, 1e-15);
  EXPECT_NEAR(b.max.z(), H / 2, 1e-15);
}

TEST(MakeCup, RejectsImpossibleSizes) {
  EXPECT_THROW(MakeCup(0.03, 0.06, 0.03, 0.01, 32), std::invalid_argument);   // wall = radius
  EXPECT_THROW(MakeCup(0.03, 0.06, 0.005, 0.06, 32), std::invalid_argument);  // floor = height
  EXPECT_THROW(MakeCup(0.03, 0.06, 0.005, 0.01, 2), std::invalid_argument);
  EXPECT_THROW(MakeCup(-0.03, 0.06, 0.005, 0.01, 32), std::invalid_argument);
}

TEST(MakeBlockWithHole, RoundAndSquareHolesAreGenusOne) {
  const Vector3 h(0.04, 0.03, 0.02);
  for (bool round : {true, false}) {
    const int n = round ? 32 : 4;
    const TriangleMesh block = MakeBlockWithHole(h, 0.0105, round, n);
    EXPECT_EQ(ExpectSolid(block), 1) << block.name;
    EXPECT_EQ(block.num_triangles(), 8 * n);
    const double hole_area = round ? 0.5 * n * std::sin(2.0 * M_PI / n) * 0.0105 * 0.0105
                                   : 4.0 * 0.0105 * 0.0105;
    EXPECT_NEAR(SignedVolume(block), (4.0 * h.x() * h.y() - hole_area) * 2.0 * h.z(), 1e-12)
        << block.name;
    // The top face faces up everywhere (no folded triangles in the annulus).
    for (const auto& t : block.triangles) {
      const Vector3 a = block.vertices[t[0]], b = block.vertices[t[1]], c = block.vertices[t[2]];
      if (a.z() == h.z() && b.z() == h.z() && c.z() == h.z()) {
        EXPECT_GT((b - a).cross(c - a).z(), 0.0);
      }
    }
  }
}

TEST(MakeBlockWithHole, RejectsBadHoles) {
  EXPECT_THROW(MakeBlockWithHole(Vector3(0.04, 0.03, 0.02), 0.03, true, 32), std::invalid_argument);
  EXPECT_THROW(MakeBlockWithHole(Vector3(0.04, 0.04, 0.02), 0.01, true, 30), std::invalid_argument);
  EXPECT_THROW(MakeBlockWithHole(Vector3(0.04, 0.04, 0.02), 0.01, true, 4), std::invalid_argument);
}

TEST(MakeLRod, IsTheUnionOfTwoBars) {
  const double ax = 0.06, ay = 0.04, w = 0.01, t = 0.008;
  const TriangleMesh rod = MakeLRod(ax, ay, w, t);
  EXPECT_EQ(ExpectSolid(rod), 0);
  EXPECT_EQ(rod.num_triangles(), 20);
  // Bar along x from -w/2 to ax, plus the y arm above it from w/2 to ay.
  const double area = (ax + w / 2) * w + (ay - w / 2) * w;
  EXPECT_NEAR(SignedVolume(rod), area * t, 1e-15);
  EXPECT_THROW(MakeLRod(0.004, 0.04, 0.01, 0.008), std::invalid_argument);
}

TEST(MakeSpoon, ClosedNonConvexWithABowl) {
  SpoonDimensions d;
  const TriangleMesh spoon = MakeSpoon(d);
  EXPECT_EQ(ExpectSolid(spoon), 0);
  const int nx = d.segments_along + 3, ny = d.segments_across + 1;  // grid columns and rows
  EXPECT_EQ(spoon.num_triangles(), 4 * (nx - 1) * (ny - 1) + 4 * (nx - 1 + ny - 1));
  EXPECT_EQ(spoon.num_triangles(), 216);
  const MeshBounds b = ComputeBounds(spoon);
  EXPECT_NEAR(b.min.x(), 0.0, 1e-15);
  EXPECT_LE(b.max.x(), d.length);
  EXPECT_GT(b.max.x(), d.length - 0.1 * d.bowl_length);
  EXPECT_NEAR(b.max.y(), 0.5 * d.bowl_width, 0.02 * d.bowl_width);
  // The bowl: the top surface dips by the bowl depth at the bowl centre, so
  // the mesh is not convex (a point between two rim vertices is outside).
  EXPECT_NEAR(b.min.z(), -0.5 * d.thickness - d.bowl_depth, 0.1 * d.bowl_depth);
  EXPECT_NEAR(b.max.z(), 0.5 * d.thickness, 1e-15);
  SpoonDimensions bad = d;
  bad.bowl_width = d.handle_width;
  EXPECT_THROW(MakeSpoon(bad), std::invalid_argument);
  bad = d;
  bad.bowl_length = d.length;
  EXPECT_THROW(MakeSpoon(bad), std::invalid_argument);
}

}  // namespace
}  // namespace pd
