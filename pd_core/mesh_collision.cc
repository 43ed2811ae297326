#include "pd_core/mesh_collision.h"

#include "pd_core/box_overlap.h"
#include "pd_core/bvh_pair_traversal.h"
#include "pd_core/solid_containment.h"
#include "pd_core/triangle_geometry.h"

namespace pd {

bool SurfacesIntersect(const ModelPair& pair, const Vector3& offset_S) {
  bool hit = false;
  const bool use_list =
      pair.candidates && pair.candidates->Covers(pair, offset_S, offset_S, 0.0);
  ForEachLeafPair(
      pair, use_list,
      [&](const BvhNode& a, const BvhNode& b) {
        return BoxesWithin(ProbeBox(a, pair.X_SP, offset_S), b, 0.0);
      },
      [&](int tp, int ts) {
        Vector3 p[3], s[3];
        pair.ProbeTriangle(tp, offset_S, p);
        pair.SceneTriangle(ts, s);
        hit = TrianglesIntersect(p[0], p[1], p[2], s[0], s[1], s[2]);
        return !hit;
      });
  return hit;
}

bool InCollision(const ModelPair& pair, const Vector3& offset_S) {
  // No surface crossing: disjoint, or a part of one wholly inside the other.
  return SurfacesIntersect(pair, offset_S) || AnyComponentInside(pair, offset_S);
}

}  // namespace pd
