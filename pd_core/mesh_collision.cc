#include "pd_core/mesh_collision.h"

#include "pd_core/box_overlap.h"
#include "pd_core/bvh_pair_traversal.h"
#include "pd_core/point_in_mesh.h"
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
  if (SurfacesIntersect(pair, offset_S)) return true;
  // No surface crossing: either disjoint or one solid wholly inside the other,
  // so testing a single vertex of each decides.
  if (pair.S.closed() && pair.P.mesh().num_vertices() > 0 &&
      PointInsideMesh(pair.S, pair.ProbeVertex(0, offset_S)))
    return true;
  if (pair.P.closed() && pair.S.mesh().num_vertices() > 0) {
    // Scene vertex 0 in P's frame: R_SP^T (p_S - p_SP - offset_S).
    const Vector3 p_P = pair.X_SP.R_SP.transpose() *
                        (pair.S.mesh().vertices[0] - pair.X_SP.p_SP - offset_S);
    if (PointInsideMesh(pair.P, p_P)) return true;
  }
  return false;
}

}  // namespace pd
