#include "pd_core/polydepth/depth_lower_bound.h"

#include "pd_core/proximity/point_clearance.h"
#include "pd_core/proximity/point_in_mesh.h"

namespace pd {

bool ProvesDepthAtLeast(const ModelPair& pair, const std::vector<ContactConstraint>& at_answer,
                        double r, int max_vertices) {
  if (!(r > 0.0)) return true;
  int tried = 0;
  for (const ContactConstraint& c : at_answer) {
    if (tried >= max_vertices) break;
    // The vertex, in the frame of the model whose solid it must be inside.
    const CollisionModel* solid = nullptr;
    Vector3 p;
    if (c.kind == FeaturePairKind::kVertexFace && pair.S.closed()) {
      solid = &pair.S;
      p = pair.ProbeVertex(c.feature_P, Vector3::Zero());
    } else if (c.kind == FeaturePairKind::kFaceVertex && pair.P.closed()) {
      solid = &pair.P;
      p = pair.SceneVertexInP(c.feature_S, Vector3::Zero());
    } else {
      continue;
    }
    ++tried;
    // The clear ball first (cheap when it fails: it stops at the first
    // triangle in reach), then which side of the surface the ball is on.
    if (SurfaceFartherThan(*solid, p, r, pair.counters) && PointInsideMesh(*solid, p)) return true;
  }
  return false;
}

}  // namespace pd
