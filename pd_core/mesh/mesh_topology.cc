#include "pd_core/mesh/mesh_topology.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

namespace pd {
namespace {

uint64_t EdgeKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(a) << 32) | static_cast<uint32_t>(b);
}

}  // namespace

MeshTopology ComputeTopology(const TriangleMesh& mesh) {
  MeshTopology topo;
  const int nt = mesh.num_triangles();
  topo.triangle_edges.resize(nt);
  std::unordered_map<uint64_t, int> index;
  index.reserve(static_cast<size_t>(nt) * 2);
  std::vector<int> face_count;
  for (int t = 0; t < nt; ++t) {
    const auto& tri = mesh.triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] ||
        FaceNormal(mesh, t).isZero()) {
      ++topo.num_degenerate_triangles;
    }
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3];
      auto [it, inserted] = index.emplace(EdgeKey(a, b), static_cast<int>(topo.edges.size()));
      if (inserted) {
        MeshEdge e;
        e.v0 = std::min(a, b);
        e.v1 = std::max(a, b);
        e.f0 = t;
        topo.edges.push_back(e);
        face_count.push_back(1);
      } else {
        MeshEdge& e = topo.edges[it->second];
        if (face_count[it->second] == 1) e.f1 = t;
        ++face_count[it->second];
      }
      topo.triangle_edges[t][k] = it->second;
    }
  }
  for (int c : face_count) {
    if (c == 1) ++topo.num_boundary_edges;
    if (c > 2) ++topo.num_nonmanifold_edges;
  }
  return topo;
}

std::string MeshTopology::Describe() const {
  if (closed()) return "closed manifold";
  std::string s = "open or non-manifold:";
  if (num_boundary_edges) s += " " + std::to_string(num_boundary_edges) + " boundary edges";
  if (num_nonmanifold_edges)
    s += " " + std::to_string(num_nonmanifold_edges) + " non-manifold edges";
  return s;
}

}  // namespace pd
