#pragma once
// Containment between a probe and a scene object whose surfaces do not
// cross: then each connected component of either mesh lies wholly inside or
// wholly outside the other's solid, so one vertex per component
// (CollisionModel::component_vertices) decides, in both directions. Meshes
// with any number of parts (CAD assemblies, scans, CGAL's 26-part bones.off)
// are covered: a part swallowed whole by the other solid is found even when
// another part is far away.
#include "pd_core/proximity/model_pair.h"

namespace pd {

// With the probe moved by offset_S (m, in S): a component of the probe
// inside the scene's solid (scene closed), or a component of the scene
// inside the probe's solid (probe closed). Only meaningful where the
// surfaces do not cross (see InCollision).
bool AnyComponentInside(const ModelPair& pair, const Vector3& offset_S);

}  // namespace pd
