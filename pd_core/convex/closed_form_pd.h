#pragma once
// Exact penetration depth in closed form for the pairs that have one (probe
// P at X_WP, scene S at X_WS, world frame, metres):
//  - any bounded geometry against a half-space scene: the deepest point of P
//    below the plane is its support point along -n (hull vertices for
//    meshes, convex or not); PD = its depth, translation along n. Exact for
//    any shape: every translation t lifts that point by n·t <= |t|.
//  - sphere / capsule against sphere / capsule: swept spheres around a point
//    or a segment; PD = r_P + r_S - distance of the cores, along the closest
//    points (cores crossing: r_P + r_S along the common perpendicular).
//  - sphere against box (either order): distance from the sphere centre to
//    the box rounded by the radius.
// Touching counts as free (in_collision = false, depth 0).
#include "pd_core/geometry/geometry.h"
#include "pd_core/convex/pair_pd_answer.h"

namespace pd {

// Whether ClosedFormPenetrationDepth handles this (probe, scene) kind pair.
bool HasClosedFormPd(ShapeKind probe, ShapeKind scene);

// Throws std::invalid_argument for a pair HasClosedFormPd rejects.
PairPdAnswer ClosedFormPenetrationDepth(const Geometry& probe, const Isometry3& X_WP,
                                        const Geometry& scene, const Isometry3& X_WS);

}  // namespace pd
