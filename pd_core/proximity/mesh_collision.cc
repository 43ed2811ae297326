#include "pd_core/proximity/mesh_collision.h"

#include <algorithm>

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

// The leaf pairs near offset_S (leaf_pairs_near.h) from the roots, or the
// descent below the node pair (root_P, root_S): true at the first
// intersecting triangle pair, whose leaf pair goes to *leaf_P, *leaf_S.
bool LeafPairsIntersect(const ModelPair& pair, const Vector3& offset_S,
                        PlacedProbeTriangles& placed, CollisionWitness* witness, int32_t root_P,
                        int32_t root_S, int32_t* leaf_P, int32_t* leaf_S) {
  bool hit = false;
  ProbeBoxMemo probe_box(pair.X_SP, offset_S, pair.probe_boxes, pair.P.bvh().nodes().data());
  auto test = [&](const BvhNode& a, const BvhNode& b, double* key) {
    return NodesWithin(probe_box(a), a, b, 0.0, key);  // deepest overlap first
  };
  auto on_leaf = [&](int ip, int is) {
    return ForEachTrianglePair(pair.P.bvh(), pair.S.bvh(), ip, is, [&](int tp, int ts) {
      hit = TrianglePairIntersects(pair, placed, tp, ts);
      if (hit) {
        if (witness) *witness = {tp, ts};
        *leaf_P = ip;
        *leaf_S = is;
      }
      return !hit;
    });
  };
  if (root_P >= 0)
    DescendBvhPair(pair.P.bvh(), pair.S.bvh(), test, [](double) { return true; }, on_leaf,
                   pair.counters, root_P, root_S);
  else
    ForEachLeafPairNear(pair, offset_S, offset_S, 0.0, test, on_leaf);
  return hit;
}

// The node `levels` above `leaf` on its path from the root (the root when
// the path is shorter). Nodes are stored depth-first: the left child of i
// is i + 1, so the path follows the right child exactly when leaf lies at
// or past it.
int32_t AncestorOf(const Bvh& bvh, int32_t leaf, int levels) {
  const auto& nodes = bvh.nodes();
  int32_t path[64];
  int n = 0;
  for (int32_t i = 0;;) {
    path[n++] = i;
    if (i == leaf || nodes[i].is_leaf() || n == 64) break;
    i = leaf < nodes[i].right_or_first ? i + 1 : nodes[i].right_or_first;
  }
  return path[std::max(0, n - 1 - levels)];
}

// IntersectionHint's regions lie this many levels above the leaf pair of a
// crossing, in each BVH. On 48 random cold queries of 11 real pairs of
// 3k-20k triangles (same answers), against descents from the roots: with
// 4 regions, total work -2% (knot1_6k) to -28% and -26% (dino_femur,
// homer_triceratops: shallow answers, whose probes all cross the surfaces
// near the contact), -12% on average; 1 region: -7%, 2: -9%, 8: as 4; 5
// and 7 levels: no better.
constexpr int kHintLevels = 6;

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
  int32_t leaf_P, leaf_S;
  return LeafPairsIntersect(pair, offset_S, placed, witness, -1, -1, &leaf_P, &leaf_S);
}

bool InCollision(const ModelPair& pair, const Vector3& offset_S, CollisionWitness* witness,
                 const CollisionWitness* earlier, int num_earlier) {
  // No surface crossing: disjoint, or a part of one wholly inside the other.
  WorkScope scope(pair.counters, QueryKind::kCollision);
  return SurfacesIntersect(pair, offset_S, witness, earlier, num_earlier) ||
         AnyComponentInside(pair, offset_S);
}

void IntersectionHint::MoveToFront(int from, NodePair region) {
  // A new region drops the oldest when full.
  const int last = std::min(from, kCapacity - 1);
  for (int k = last; k > 0; --k) regions[k] = regions[k - 1];
  regions[0] = region;
  size = std::max(size, std::min(from + 1, kCapacity));
}

bool InCollisionExpectingDepth(const ModelPair& pair, const Vector3& offset_S) {
  WorkScope scope(pair.counters, QueryKind::kCollision);
  if (InnerSpheresOverlap(pair, offset_S)) return true;
  IntersectionHint* hint = pair.intersection_hint;
  if (hint == nullptr) return InCollision(pair, offset_S);
  PlacedProbeTriangles placed(pair, offset_S);
  int32_t leaf_P, leaf_S;
  // Below each region first, the most recent first; then everything from
  // the roots (the regions' subtrees again: a miss costs those tests twice,
  // which skipping them would save only ~0.5%).
  auto crossed = [&](int from) {
    hint->MoveToFront(from, {AncestorOf(pair.P.bvh(), leaf_P, kHintLevels),
                             AncestorOf(pair.S.bvh(), leaf_S, kHintLevels)});
    return true;
  };
  for (int k = 0; k < hint->size; ++k)
    if (LeafPairsIntersect(pair, offset_S, placed, nullptr, hint->regions[k].ip,
                           hint->regions[k].is, &leaf_P, &leaf_S))
      return crossed(k);
  if (LeafPairsIntersect(pair, offset_S, placed, nullptr, -1, -1, &leaf_P, &leaf_S))
    return crossed(hint->size);
  return AnyComponentInside(pair, offset_S);
}

}  // namespace pd
