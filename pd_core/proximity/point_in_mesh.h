#pragma once
// Solid containment for closed meshes: is a point inside? The parity of the
// crossings of a ray with the surface, counted through the BVH, is exact for
// a closed mesh (every edge shared by exactly two faces) whenever the ray
// passes clear of edges and vertices: every such ray gives the same parity,
// so the first clean one decides. A ray that passes within rounding of an
// edge or vertex, or runs in a face's plane, is re-cast along another of
// seven fixed directions (each leaning toward the nearest face of the root
// box: short rays visit few boxes). If no ray is clean (the point lies on or
// within rounding of an edge or vertex), the answer fails closed: a point on
// the surface is inside (the solid is closed), any other point is decided by
// the exact winding number (the sum of the triangles' solid angles,
// O(triangles): rare).
#include "pd_core/mesh/collision_model.h"
#include "pd_core/proximity/bvh_descent.h"

namespace pd {

// p_M in the model's frame (m). Meaningful only for closed meshes; a point
// on the surface counts as inside.
bool PointInsideMesh(const CollisionModel& model, const Vector3& p_M);

// One ray's verdict.
enum class RayCount {
  kClean,      // `crossings` is exact
  kGrazed,     // passed within rounding of an edge or vertex, or along a face
  kOnSurface,  // the ray's origin lies on a triangle (within rounding)
};
struct RayCrossings {
  RayCount status = RayCount::kClean;
  int crossings = 0;  // surface crossings at s > 0 (valid when kClean)
};

// Crossings of the ray p_M + s * d_M (s > 0, d_M unit, model frame) with the
// surface. The BVH descent (bvh_descent.h) keeps at most stack_capacity
// pending nodes (clamped to [0, kBvhStackCapacity]); a subtree that would
// need more is scanned triangle by triangle instead, so a BVH of any depth
// is traversed correctly with a fixed, checked stack.
RayCrossings CountRayCrossings(const CollisionModel& model, const Vector3& p_M, const Vector3& d_M,
                               int stack_capacity = kBvhStackCapacity);

// Generalized winding number of the closed surface around p_M: the sum of the
// triangles' signed solid angles over 4 pi (1 inside, 0 outside for a closed,
// outward-oriented mesh; 0.5 on a face). O(triangles).
double WindingNumber(const CollisionModel& model, const Vector3& p_M);

}  // namespace pd
