#pragma once
// Test references without a BVH: every triangle pair of a probe and a scene
// whose axis-aligned boxes overlap, and real meshes normalised like the
// benchmark's (0.1 m bounding sphere about the box centre).
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "pd_core/mesh/load_mesh.h"
#include "pd_core/proximity/model_pair.h"

namespace pd::test {

inline std::shared_ptr<const CollisionModel> LoadCentredModel(const std::string& path) {
  TriangleMesh mesh = LoadMesh(path).mesh;
  const MeshBounds b = ComputeBounds(mesh);
  double r = 0.0;
  for (const Vector3& v : mesh.vertices) r = std::max(r, (v - b.center()).norm());
  for (Vector3& v : mesh.vertices) v = 0.1 * (v - b.center()) / r;
  return CollisionModel::Build(std::move(mesh));
}

// Calls fn(tp, ts) for every probe triangle (translated by offset_S, its box
// grown to cover a further translation by sweep_S) and scene triangle whose
// boxes overlap, until fn returns false.
template <typename Fn>
void ForEachOverlappingTrianglePair(const ModelPair& pair, const Vector3& offset_S,
                                    const Vector3& sweep_S, Fn&& fn) {
  const int n_P = pair.P.mesh().num_triangles(), n_S = pair.S.mesh().num_triangles();
  std::vector<Vector3> lo_S(n_S), hi_S(n_S);
  for (int ts = 0; ts < n_S; ++ts) {
    Vector3 s[3];
    pair.SceneTriangle(ts, s);
    lo_S[ts] = s[0].cwiseMin(s[1]).cwiseMin(s[2]);
    hi_S[ts] = s[0].cwiseMax(s[1]).cwiseMax(s[2]);
  }
  for (int tp = 0; tp < n_P; ++tp) {
    Vector3 p[3];
    pair.ProbeTriangle(tp, offset_S, p);
    Vector3 lo = p[0].cwiseMin(p[1]).cwiseMin(p[2]), hi = p[0].cwiseMax(p[1]).cwiseMax(p[2]);
    lo = lo.cwiseMin(lo + sweep_S).array() - 1e-12;
    hi = hi.cwiseMax(hi + sweep_S).array() + 1e-12;
    for (int ts = 0; ts < n_S; ++ts) {
      if ((lo.array() > hi_S[ts].array()).any() || (hi.array() < lo_S[ts].array()).any()) continue;
      if (!fn(tp, ts)) return;
    }
  }
}

}  // namespace pd::test
