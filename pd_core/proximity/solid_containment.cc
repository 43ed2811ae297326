#include "pd_core/proximity/solid_containment.h"

#include "pd_core/proximity/point_in_mesh.h"

namespace pd {

bool AnyComponentInside(const ModelPair& pair, const Vector3& offset_S) {
  WorkScope scope(pair.counters, QueryKind::kCollision);
  if (pair.S.closed()) {
    for (int v : pair.P.component_vertices())
      if (PointInsideMesh(pair.S, pair.ProbeVertex(v, offset_S))) return true;
  }
  if (pair.P.closed()) {
    // Scene vertex in P's frame: R_SP^T (p_S - p_SP - offset_S).
    for (int v : pair.S.component_vertices()) {
      const Vector3 p_P = pair.X_SP.R_SP.transpose() *
                          (pair.S.mesh().vertices[v] - pair.X_SP.p_SP - offset_S);
      if (PointInsideMesh(pair.P, p_P)) return true;
    }
  }
  return false;
}

}  // namespace pd
