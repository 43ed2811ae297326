#pragma once
// The reference's surface test: triangle pairs by orientation predicates
// (recomputed in quad precision near zero), sort-and-sweep over triangle
// boxes. Part of the slow independent reference (reference_pd.h).
#include "pd_core/reference/placed_pair.h"

namespace pd {
namespace reference {

// Any triangle of g.P intersecting any triangle of g.S (closed triangles).
bool SurfacesIntersect(const PairGeometry& g);

}  // namespace reference
}  // namespace pd
