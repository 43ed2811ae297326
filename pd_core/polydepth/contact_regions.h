#pragma once
// Groups the contact constraints at a PD answer into contact regions with a
// local PD (d·n_i) n_i each, expressed in world at the query pose: what the
// haptic wrench needs for torque.
#include <vector>

#include "pd_core/polydepth/contact_constraints.h"
#include "pd_core/polydepth/penetration_result.h"

namespace pd {

// constraints: localised at the answer q_S (probe translation in S).
// X_WS: scene pose. merge_distance (m): features farther apart than this stay
// in separate regions even with equal normals. Fills result->regions.
void GroupContactRegions(const std::vector<ContactConstraint>& constraints, const Vector3& q_S,
                         const Isometry3& X_WS, double merge_distance,
                         PenetrationResult* result);

}  // namespace pd
