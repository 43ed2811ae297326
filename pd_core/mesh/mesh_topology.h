#pragma once
// Edge adjacency of a triangle mesh and the closed/manifold report that
// decides whether solid containment tests are meaningful for it.
#include <array>
#include <string>
#include <vector>

#include "pd_core/mesh/mesh.h"

namespace pd {

struct MeshEdge {
  int v0 = -1, v1 = -1;  // v0 < v1
  int f0 = -1, f1 = -1;  // adjacent faces; f1 = -1 on a boundary edge
};

struct MeshTopology {
  std::vector<MeshEdge> edges;
  // For each triangle, the indices into `edges` of its edges (v0v1, v1v2, v2v0).
  std::vector<std::array<int, 3>> triangle_edges;
  int num_boundary_edges = 0;     // edges with one face
  int num_nonmanifold_edges = 0;  // edges with three or more faces
  int num_degenerate_triangles = 0;  // zero area or repeated vertex
  bool closed() const { return num_boundary_edges == 0 && num_nonmanifold_edges == 0; }
  // One line summary for logs, e.g. "closed manifold" or "open: 12 boundary edges".
  std::string Describe() const;
};

MeshTopology ComputeTopology(const TriangleMesh& mesh);

}  // namespace pd
