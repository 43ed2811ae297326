#include "pd_core/reference/placed_pair.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pd {
namespace reference {
namespace {

// Feature tests accept points this far (relative to the pair's extent) outside
// a triangle or segment, so that rounding never drops a touching event.
constexpr double kRelativeLengthTol = 1e-12;

// Without the surfaces touching, each connected piece of a mesh lies wholly
// inside or outside the other mesh, so one vertex per piece decides containment.
std::vector<int> ComponentVertices(const TriangleMesh& mesh) {
  std::vector<int> parent(mesh.vertices.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) used[t[k]] = 1;
    const int r0 = find(t[0]);
    parent[find(t[1])] = r0;
    parent[find(t[2])] = r0;
  }
  std::vector<int> reps;
  for (int v = 0; v < static_cast<int>(parent.size()); ++v) {
    if (used[v] && find(v) == v) reps.push_back(v);
  }
  return reps;
}

double BoundingRadius(const TriangleMesh& mesh) {
  const MeshBounds b = ComputeBounds(mesh);
  const Vector3 c = b.center();
  double r2 = 0.0;
  for (const Vector3& v : mesh.vertices) r2 = std::max(r2, (v - c).squaredNorm());
  return std::sqrt(r2);
}

PlacedMesh Place(const TriangleMesh& mesh, const Isometry3& X_WM, const Vector3& p_WO,
                 bool closed) {
  PlacedMesh m;
  m.p_OV.reserve(mesh.vertices.size());
  for (const Vector3& p_MV : mesh.vertices) m.p_OV.push_back(X_WM * p_MV - p_WO);
  m.triangles = &mesh.triangles;
  m.component_vertices = ComponentVertices(mesh);
  m.closed = closed;
  return m;
}

}  // namespace

PairGeometry MakePair(const TriangleMesh& probe, const Isometry3& X_WP, bool probe_closed,
                      const TriangleMesh& scene, const Isometry3& X_WS, bool scene_closed) {
  Vector3 lo = Vector3::Constant(kInf), hi = Vector3::Constant(-kInf);
  for (const Vector3& v : probe.vertices) {
    lo = lo.cwiseMin(X_WP * v);
    hi = hi.cwiseMax(X_WP * v);
  }
  for (const Vector3& v : scene.vertices) {
    lo = lo.cwiseMin(X_WS * v);
    hi = hi.cwiseMax(X_WS * v);
  }
  const Vector3 p_WO = (probe.vertices.empty() && scene.vertices.empty())
                           ? Vector3::Zero()
                           : Vector3(0.5 * (lo + hi));
  PairGeometry g;
  g.P = Place(probe, X_WP, p_WO, probe_closed);
  g.S = Place(scene, X_WS, p_WO, scene_closed);
  double extent = 0.0;
  for (const auto* m : {&g.P, &g.S}) {
    for (const Vector3& p : m->p_OV) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  }
  g.eps_len = kRelativeLengthTol * std::max(extent, std::numeric_limits<double>::min());
  g.size = BoundingRadius(probe) + BoundingRadius(scene);
  return g;
}

}  // namespace reference
}  // namespace pd
