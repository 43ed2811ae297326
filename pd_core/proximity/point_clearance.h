#pragma once
// Point clearance: is a ball around a point clear of a model's surface?
#include "pd_core/mesh/collision_model.h"
#include "pd_core/proximity/bvh_pair_descent.h"

namespace pd {

// True if no triangle of the model comes within `radius` (m) of p_M (model
// frame, m): the open ball lies wholly inside or wholly outside a closed
// model's solid. Stops at the first triangle within reach. Counts its node
// tests as box tests and its point-triangle tests as triangle tests.
bool SurfaceFartherThan(const CollisionModel& model, const Vector3& p_M, double radius,
                        ProximityCounters* counters = nullptr);

// The distance (m) from p_M (model frame) to the nearest point of the
// model's surface, or `max_distance` if no triangle comes nearer. One
// descent, its reach shrinking to the nearest triangle found so far.
double SurfaceDistance(const CollisionModel& model, const Vector3& p_M, double max_distance,
                       ProximityCounters* counters = nullptr);

}  // namespace pd
