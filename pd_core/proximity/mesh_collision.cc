#include "pd_core/proximity/mesh_collision.h"

#include "pd_core/proximity/box_overlap.h"
#include "pd_core/proximity/inner_sphere_overlap.h"
#include "pd_core/proximity/leaf_pairs_near.h"
#include "pd_core/proximity/placed_probe_triangles.h"
#include "pd_core/proximity/solid_containment.h"
#include "pd_core/proximity/triangle_geometry.h"

namespace pd {

namespace {

bool TrianglePairIntersects(const ModelPair& pair, PlacedProbeTriangles& placed, int tp, int ts) {
  const Vector3* p = placed(tp).p;
  Vector3 s[3];
  pair.SceneTriangle(ts, s);
  if (pair.counters) ++pair.counters->triangle_tests;
  return TrianglesIntersect(p[0], p[1], p[2], s[0], s[1], s[2]);
}

// The triangle and its edge-neighbours (up to 4), into out; returns the count.
int WithNeighbours(const CollisionModel& m, int t, int out[4]) {
  int n = 0;
  out[n++] = t;
  for (int e : m.topology().triangle_edges[t]) {
    const MeshEdge& edge = m.topology().edges[e];
    const int other = edge.f0 == t ? edge.f1 : edge.f0;
    if (other >= 0) out[n++] = other;
  }
  return n;
}

bool WitnessIntersects(const ModelPair& pair, PlacedProbeTriangles& placed,
                       CollisionWitness* witness) {
  if (witness == nullptr || witness->tp < 0 || witness->tp >= pair.P.mesh().num_triangles() ||
      witness->ts < 0 || witness->ts >= pair.S.mesh().num_triangles())
    return false;
  // The contact slides a little between queries: the pair that
  // intersected last time or one of its neighbour pairs usually still does.
  int near_P[4], near_S[4];
  const int np = WithNeighbours(pair.P, witness->tp, near_P);
  const int ns = WithNeighbours(pair.S, witness->ts, near_S);
  for (int i = 0; i < np; ++i)
    for (int j = 0; j < ns; ++j)
      if (TrianglePairIntersects(pair, placed, near_P[i], near_S[j])) {
        *witness = {near_P[i], near_S[j]};
        return true;
      }
  return false;
}

}  // namespace

bool WitnessIntersects(const ModelPair& pair, const Vector3& offset_S,
                       CollisionWitness* witness) {
  WorkScope scope(pair.counters, QueryKind::kCollision);
  PlacedProbeTriangles placed(pair, offset_S);
  return WitnessIntersects(pair, placed, witness);
}

bool SurfacesIntersect(const ModelPair& pair, const Vector3& offset_S, CollisionWitness* witness,
                       const CollisionWitness* earlier, int num_earlier) {
  WorkScope scope(pair.counters, QueryKind::kCollision);
  PlacedProbeTriangles placed(pair, offset_S);
  for (int i = 0; i < num_earlier; ++i) {
    CollisionWitness w = earlier[i];
    if (WitnessIntersects(pair, placed, &w)) {
      *witness = w;
      return true;
    }
  }
  if (WitnessIntersects(pair, placed, witness)) return true;
  bool hit = false;
  ProbeBoxMemo probe_box(pair.X_SP, offset_S);
  ForEachLeafPairNear(
      pair, offset_S, offset_S, 0.0,
      [&](const BvhNode& a, const BvhNode& b, double* key) {
        return NodesWithin(probe_box(a), a, b, 0.0, key);  // deepest overlap first
      },
      [&](int ip, int is) {
        return ForEachTrianglePair(pair.P.bvh(), pair.S.bvh(), ip, is, [&](int tp, int ts) {
          hit = TrianglePairIntersects(pair, placed, tp, ts);
          if (hit && witness) *witness = {tp, ts};
          return !hit;
        });
      });
  return hit;
}

bool InCollision(const ModelPair& pair, const Vector3& offset_S, CollisionWitness* witness,
                 const CollisionWitness* earlier, int num_earlier) {
  // No surface crossing: disjoint, or a part of one wholly inside the other.
  WorkScope scope(pair.counters, QueryKind::kCollision);
  return SurfacesIntersect(pair, offset_S, witness, earlier, num_earlier) ||
         AnyComponentInside(pair, offset_S);
}

bool InCollisionExpectingDepth(const ModelPair& pair, const Vector3& offset_S) {
  WorkScope scope(pair.counters, QueryKind::kCollision);
  return InnerSpheresOverlap(pair, offset_S) || InCollision(pair, offset_S);
}

}  // namespace pd
