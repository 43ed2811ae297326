#pragma once
// Test references without a BVH: every triangle pair of a probe and a scene
// whose axis-aligned boxes overlap or that lie within a distance, triangle
// distances, the leaf of each triangle, and real meshes normalised like the
// benchmark's (0.1 m bounding sphere about the box centre).
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "pd_core/mesh/load_mesh.h"
#include "pd_core/proximity/model_pair.h"
#include "pd_core/proximity/triangle_geometry.h"

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

// Distance between two triangles (m): zero if they intersect, else the
// smallest of the vertex-triangle and edge-edge distances.
inline double TriangleDistance(const Vector3 a[3], const Vector3 b[3]) {
  if (TrianglesIntersect(a[0], a[1], a[2], b[0], b[1], b[2])) return 0.0;
  double d = 1e300;
  for (int i = 0; i < 3; ++i) {
    d = std::min(d, (a[i] - ClosestPointOnTriangle(a[i], b[0], b[1], b[2])).norm());
    d = std::min(d, (b[i] - ClosestPointOnTriangle(b[i], a[0], a[1], a[2])).norm());
    for (int j = 0; j < 3; ++j) {
      double s, t;
      Vector3 p, q;
      d = std::min(d, std::sqrt(ClosestSegmentSegment(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3],
                                                      &s, &t, &p, &q)));
    }
  }
  return d;
}

// Calls fn(tp, ts) for every probe triangle (translated by offset_S) and
// scene triangle within `distance` (m) of each other, over all pairs.
template <typename Fn>
void ForEachTrianglePairWithin(const ModelPair& pair, const Vector3& offset_S, double distance,
                               Fn&& fn) {
  const int n_P = pair.P.mesh().num_triangles(), n_S = pair.S.mesh().num_triangles();
  for (int tp = 0; tp < n_P; ++tp) {
    Vector3 p[3];
    pair.ProbeTriangle(tp, offset_S, p);
    const Vector3 lo = p[0].cwiseMin(p[1]).cwiseMin(p[2]).array() - distance;
    const Vector3 hi = p[0].cwiseMax(p[1]).cwiseMax(p[2]).array() + distance;
    for (int ts = 0; ts < n_S; ++ts) {
      Vector3 t[3];
      pair.SceneTriangle(ts, t);
      if ((lo.array() > t[0].cwiseMax(t[1]).cwiseMax(t[2]).array()).any() ||
          (hi.array() < t[0].cwiseMin(t[1]).cwiseMin(t[2]).array()).any())
        continue;
      if (TriangleDistance(p, t) <= distance) fn(tp, ts);
    }
  }
}

// The leaf node holding each triangle of a model's hierarchy.
inline std::vector<int> LeafOfTriangle(const Bvh& bvh, int num_triangles) {
  std::vector<int> leaf(num_triangles, -1);
  for (size_t i = 0; i < bvh.nodes().size(); ++i) {
    const BvhNode& n = bvh.nodes()[i];
    for (int k = 0; k < n.count; ++k) leaf[bvh.order()[n.right_or_first + k]] = i;
  }
  return leaf;
}

}  // namespace pd::test
