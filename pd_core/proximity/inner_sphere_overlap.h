#pragma once
// Collision certificate from the models' inner spheres (inner_spheres.h):
// an open ball inside the probe's solid overlapping one inside the scene's
// proves the solids overlap, with no BVH test. Deep configurations (a cold
// search's probes well inside its best answer) are mostly settled this way;
// shallow ones never are (the spheres keep clear of the surfaces), so only
// callers that expect depth ask.
#include "pd_core/proximity/model_pair.h"

namespace pd {

// True if an inner sphere of the probe, translated by offset_S (m, in S),
// overlaps an inner sphere of the scene (false, not a verdict, otherwise).
// Counts one box test per probe sphere placed (its distance checks against
// all the scene's spheres cost about one box test).
bool InnerSpheresOverlap(const ModelPair& pair, const Vector3& offset_S);

}  // namespace pd
