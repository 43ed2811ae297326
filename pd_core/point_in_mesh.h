#pragma once
// Solid containment for closed meshes: is a point inside? Ray-crossing parity
// through the BVH, re-cast along another direction when a ray grazes an edge
// or vertex, majority of three clean casts.
#include "pd_core/collision_model.h"

namespace pd {

// p_M in the model's frame. Meaningful only for closed meshes.
bool PointInsideMesh(const CollisionModel& model, const Vector3& p_M);

}  // namespace pd
