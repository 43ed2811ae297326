#pragma once
// A certificate that a PD answer is (nearly) the shortest there is, from the
// answer's own contact. A probe vertex inside the scene's solid whose ball of
// radius r holds no scene triangle stays inside the solid under every probe
// translation shorter than r: PD >= r. Likewise a scene vertex inside the
// probe's solid. At a PD answer the touching vertices are where the probe
// was deepest along the answer, so on a contact that is locally flat their
// clearance at the query pose is the answer's length: the answer is proved
// optimal without searching other directions.
#include <vector>

#include "pd_core/polydepth/contact_constraints.h"

namespace pd {

// True if a vertex of the vertex-face or face-vertex feature pairs in
// `at_answer` (localised at a PD answer of this pose) proves PD >= r (m)
// for the pair at its pose (the probe untranslated). Tries at most
// `max_vertices` vertices. Meaningful for closed meshes only: a vertex of a
// model is tested only against a closed other model. Work goes to
// pair.counters.
bool ProvesDepthAtLeast(const ModelPair& pair, const std::vector<ContactConstraint>& at_answer,
                        double r, int max_vertices = 4);

}  // namespace pd
