// The BVH builder (pd_core/proximity/bvh.h): every triangle in exactly one
// leaf of at most kMaxLeafTriangles, every box holding its triangles; a
// split falls in the gap between unevenly sized groups of triangles (least
// surface area, not equal counts); the depth stays within about three times
// the balanced depth on input that makes every such split lopsided; and a
// node takes the mesh frame's axes where their box is smaller than the
// principal-axes box; every node's axis-aligned bounds and radius hold its
// box's corners, tight to float precision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "pd_core/proximity/bvh.h"

namespace pd {
namespace {

// A small triangle (edge ~size) in the z = 0 plane at (x, y).
void AddTriangle(TriangleMesh* mesh, double x, double y, double size) {
  const int base = mesh->num_vertices();
  mesh->vertices.push_back(Vector3(x, y, 0));
  mesh->vertices.push_back(Vector3(x + size, y, 0));
  mesh->vertices.push_back(Vector3(x, y + size, 0));
  mesh->triangles.push_back(Eigen::Vector3i(base, base + 1, base + 2));
}

// Triangles of node `index` (every leaf below it), by the leaves' slots.
std::vector<int> TrianglesBelow(const Bvh& bvh, int index) {
  const BvhNode& node = bvh.nodes()[index];
  if (node.is_leaf()) {
    return std::vector<int>(bvh.order().begin() + node.right_or_first,
                            bvh.order().begin() + node.right_or_first + node.count);
  }
  std::vector<int> out = TrianglesBelow(bvh, index + 1);
  const std::vector<int> right = TrianglesBelow(bvh, node.right_or_first);
  out.insert(out.end(), right.begin(), right.end());
  return out;
}

// True if every vertex of the node's triangles lies in its box (tolerance tol).
bool BoxHoldsItsTriangles(const Bvh& bvh, const TriangleMesh& mesh, int index, double tol) {
  const BvhNode& node = bvh.nodes()[index];
  for (int t : TrianglesBelow(bvh, index)) {
    for (int k = 0; k < 3; ++k) {
      const Vector3 p_B = node.R_MB.transpose() * (mesh.vertices[mesh.triangles[t][k]] - node.center_M);
      if ((p_B.cwiseAbs() - node.half_B).maxCoeff() > tol) return false;
    }
  }
  return true;
}

TEST(Bvh, EveryTriangleInOneLeafAndEveryBoxHoldsItsTriangles) {
  TriangleMesh mesh;
  // A rough spiral of 301 triangles of uneven spacing and size.
  for (int i = 0; i < 301; ++i) {
    const double a = 0.37 * i, r = 0.1 + 0.01 * i;
    AddTriangle(&mesh, r * std::cos(a), r * std::sin(a) + 0.001 * (i % 7), 0.01 + 0.002 * (i % 5));
  }
  const Bvh bvh(mesh);
  std::vector<int> all = TrianglesBelow(bvh, 0);
  std::sort(all.begin(), all.end());
  ASSERT_EQ(static_cast<int>(all.size()), mesh.num_triangles());
  for (int t = 0; t < mesh.num_triangles(); ++t) EXPECT_EQ(all[t], t);
  for (int i = 0; i < static_cast<int>(bvh.nodes().size()); ++i) {
    if (bvh.nodes()[i].is_leaf()) EXPECT_LE(bvh.nodes()[i].count, Bvh::kMaxLeafTriangles);
    EXPECT_TRUE(BoxHoldsItsTriangles(bvh, mesh, i, 1e-12)) << "node " << i;
  }
}

TEST(Bvh, TheRootSplitFallsInTheGapBetweenUnevenGroups) {
  // 3 triangles near x = 0 and 13 near x = 10: equal counts would put five
  // of the far group with the near one, under one box spanning the gap.
  TriangleMesh mesh;
  for (int i = 0; i < 3; ++i) AddTriangle(&mesh, 0.1 * i, 0.05 * i, 0.05);
  for (int i = 0; i < 13; ++i) AddTriangle(&mesh, 10.0 + 0.1 * i, 0.05 * (i % 3), 0.05);
  const Bvh bvh(mesh);
  const BvhNode& root = bvh.nodes()[0];
  ASSERT_FALSE(root.is_leaf());
  std::vector<int> left = TrianglesBelow(bvh, 1), right = TrianglesBelow(bvh, root.right_or_first);
  if (left.size() > right.size()) std::swap(left, right);
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(right.size(), 13u);
}

TEST(Bvh, DepthStaysBoundedWhenEveryCostSplitIsLopsided) {
  // Centroids at x = 1.5^i: all but a group's last one or two share the
  // lowest of the equal-width bins along x, so splits between bins alone
  // would peel them off one by one, a chain as deep as half the count.
  TriangleMesh mesh;
  const int n = 400;
  for (int i = 0; i < n; ++i) AddTriangle(&mesh, std::pow(1.5, i), 0.0, 0.1);
  const Bvh bvh(mesh);
  const int balanced = static_cast<int>(std::ceil(std::log2(n)));
  EXPECT_LE(bvh.depth(), 3 * balanced + 2);
  EXPECT_EQ(static_cast<int>(TrianglesBelow(bvh, 0).size()), n);
}

TEST(Bvh, ANodeTakesTheMeshAxesWhereTheirBoxIsSmaller) {
  // The unit square in z = 0 as two triangles, plus slivers along its
  // diagonal: the vertices' scatter is longest along the diagonal, whose
  // principal-axes box is a 45-degree square of side sqrt(2), twice the
  // area of the square's own axis-aligned box.
  TriangleMesh mesh;
  mesh.vertices = {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(1, 1, 0), Vector3(0, 1, 0)};
  mesh.triangles = {Eigen::Vector3i(0, 1, 2), Eigen::Vector3i(0, 2, 3)};
  for (int i = 0; i < 20; ++i) {
    const double s = 0.05 * i;
    const int base = mesh.num_vertices();
    mesh.vertices.push_back(Vector3(s, s, 0));
    mesh.vertices.push_back(Vector3(s + 0.04, s + 0.04, 0));
    mesh.vertices.push_back(Vector3(s + 0.02, s + 0.021, 0));
    mesh.triangles.push_back(Eigen::Vector3i(base, base + 1, base + 2));
  }
  const Bvh bvh(mesh);
  const BvhNode& root = bvh.nodes()[0];
  Vector3 half = root.half_B;
  std::sort(half.data(), half.data() + 3);
  EXPECT_NEAR(half[0], 0.0, 1e-12);
  EXPECT_NEAR(half[1], 0.5, 1e-12);
  EXPECT_NEAR(half[2], 0.5, 1e-12);
  EXPECT_TRUE(BoxHoldsItsTriangles(bvh, mesh, 0, 1e-12));
}

// The derived bounds (the first, cheapest tests of a node pair): per mesh
// axis the largest reach of the box's 8 corners, and the largest corner
// distance, from the box centre, rounded up to float.
TEST(Bvh, EveryNodesAxisAlignedBoundsAndRadiusHoldItsCornersTightly) {
  TriangleMesh mesh;
  for (int i = 0; i < 200; ++i) {
    const double a = 0.61 * i, r = 0.2 + 0.005 * i;
    const int base = mesh.num_vertices();
    // Triangles tilted out of every axis plane: rotated boxes.
    mesh.vertices.push_back(Vector3(r * std::cos(a), r * std::sin(a), 0.3 * std::sin(0.7 * i)));
    mesh.vertices.push_back(mesh.vertices[base] + Vector3(0.03, 0.01 * (i % 3), 0.02));
    mesh.vertices.push_back(mesh.vertices[base] + Vector3(-0.01, 0.025, 0.01 * (i % 4)));
    mesh.triangles.push_back(Eigen::Vector3i(base, base + 1, base + 2));
  }
  const Bvh bvh(mesh);
  int rotated = 0;
  for (const BvhNode& node : bvh.nodes()) {
    Vector3 reach = Vector3::Zero();
    double radius = 0.0;
    for (int c = 0; c < 8; ++c) {
      const Vector3 corner_B((c & 1 ? 1 : -1) * node.half_B.x(), (c & 2 ? 1 : -1) * node.half_B.y(),
                             (c & 4 ? 1 : -1) * node.half_B.z());
      const Vector3 d_M = node.R_MB * corner_B;
      reach = reach.cwiseMax(d_M.cwiseAbs());
      radius = std::max(radius, d_M.norm());
    }
    // Held (never below: a bound), tight to float precision.
    const Vector3 aabb = node.aabb_half_M.cast<double>();
    EXPECT_GE((aabb - reach).minCoeff(), 0.0);
    EXPECT_LE((aabb - reach).maxCoeff(), 1e-6 * reach.maxCoeff());
    EXPECT_GE(static_cast<double>(node.radius), radius);
    EXPECT_LE(static_cast<double>(node.radius), radius * (1.0 + 1e-6));
    rotated += !node.R_MB.isIdentity(1e-9);
  }
  EXPECT_GT(rotated, 0);  // the check covers boxes not aligned with M
}

}  // namespace
}  // namespace pd
