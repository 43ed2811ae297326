#pragma once
// Bounding-volume hierarchy over a mesh's triangles: oriented boxes (axes
// from the principal directions of the node's vertices, or the mesh frame's
// where that box is smaller), binary, split where the children's surface
// area is least (see bvh.cc), nodes stored depth-first (left child =
// index + 1). Oriented boxes hug the long sliver
// triangles of tessellated tubes and curved surfaces far better than
// axis-aligned ones, which is what keeps near-contact traversals short.
// Pair queries are separating-axis tests (see box_overlap.h).
#include <cstdint>
#include <vector>

#include "pd_core/mesh/mesh.h"

namespace pd {

struct BvhNode {
  Matrix3 R_MB;      // box axes B (columns) in the mesh frame M
  Vector3 center_M;  // box centre in M (m)
  Vector3 half_B;    // half extents along the box axes (m)
  // Derived from the three above (Bvh::DeriveBounds): the half extents of
  // the box's axis-aligned bounds in M and its bounding-sphere radius (m),
  // the cheap first tests of a pair (box_overlap.h). Floats rounded up
  // (never smaller than the box's): 16 bytes per node, not 32.
  Eigen::Vector3f aabb_half_M = Eigen::Vector3f::Zero();
  float radius = 0.0f;
  int32_t right_or_first = 0;  // internal: right child; leaf: first slot in order()
  int32_t count = 0;           // 0 for internal nodes, else triangles in the leaf
  bool is_leaf() const { return count > 0; }
};

class Bvh {
 public:
  static constexpr int kMaxLeafTriangles = 2;
  Bvh() = default;
  explicit Bvh(const TriangleMesh& mesh);

  const std::vector<BvhNode>& nodes() const { return nodes_; }
  // Triangle indices in leaf order; a leaf holds order()[first .. first+count).
  const std::vector<int32_t>& order() const { return order_; }
  // Levels from the root to the deepest leaf (1 for a single leaf).
  int depth() const { return depth_; }
  // Depth measured from the node links (for BVHs read from disk, whose
  // stored depth is not trusted).
  static int MeasureDepth(const std::vector<BvhNode>& nodes);
  // A BVH from given nodes (tests: hand-made, e.g. degenerate, trees). The
  // links must satisfy what Bvh builds: left child = index + 1, right child
  // beyond it, leaves indexing `order`.
  static Bvh FromNodes(std::vector<BvhNode> nodes, std::vector<int32_t> order);
  // Sets every node's aabb_half_M and radius from its box.
  static void DeriveBounds(std::vector<BvhNode>* nodes);
  bool empty() const { return nodes_.empty(); }
  size_t MemoryBytes() const {
    return nodes_.capacity() * sizeof(BvhNode) + order_.capacity() * sizeof(int32_t);
  }

 private:
  friend struct ModelCacheAccess;  // pd_core/mesh/model_cache.cc (de)serialises the nodes
  // A triangle as the builder reads it: its vertices in the mesh frame and
  // its index. The builder reorders these in place (its passes then read
  // memory in order); centroid and bounds are recomputed where needed
  // (storing them made the records twice as large for no faster build).
  struct BuildTriangle {
    Vector3 v[3];
    int32_t t;
    double centroid(int axis) const { return (v[0][axis] + v[1][axis] + v[2][axis]) / 3.0; }
    Vector3 centroid() const { return (v[0] + v[1] + v[2]) / 3.0; }
    Vector3 lo() const { return v[0].cwiseMin(v[1]).cwiseMin(v[2]); }
    Vector3 hi() const { return v[0].cwiseMax(v[1]).cwiseMax(v[2]); }
  };
  int Build(std::vector<BuildTriangle>& tris, int begin, int end, int level);
  std::vector<BvhNode> nodes_;
  std::vector<int32_t> order_;
  int depth_ = 0;
  int cost_split_levels_ = 0;  // levels split by the surface-area cost (Build)
};

// Node size for choosing which side of a node pair to descend.
inline double NodeSize2(const BvhNode& n) { return n.half_B.squaredNorm(); }

}  // namespace pd
