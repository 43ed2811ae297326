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
    for (int v : pair.S.component_vertices())
      if (PointInsideMesh(pair.P, pair.SceneVertexInP(v, offset_S))) return true;
  }
  return false;
}

}  // namespace pd
