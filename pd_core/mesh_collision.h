#pragma once
// Boolean collision of a probe against a scene object: surfaces intersect, or
// one closed solid holds the other (a probe wholly inside counts as colliding).
#include "pd_core/model_pair.h"

namespace pd {

// Any probe triangle intersecting any scene triangle, probe moved by offset_S.
bool SurfacesIntersect(const ModelPair& pair, const Vector3& offset_S);

// SurfacesIntersect, or a part of one mesh inside the other's solid, either
// way, for closed meshes (pd_core/solid_containment.h).
bool InCollision(const ModelPair& pair, const Vector3& offset_S);

}  // namespace pd
