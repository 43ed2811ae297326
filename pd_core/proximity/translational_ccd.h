#pragma once
// Exact translational continuous collision detection: the first time s in
// [0, 1] at which the probe, moved by offset_S + s * sweep_S, touches the
// scene surface. Exact per triangle pair (vertex-face, face-vertex and
// edge-edge events), no fixed step count.
#include "pd_core/proximity/model_pair.h"

namespace pd {

// Returns the first contact fraction s in [0, 1], or a negative value if the
// sweep is contact-free. Precondition: the start configuration is free
// (events are first touches; a start already intersecting is not reported).
double FirstContactAlongTranslation(const ModelPair& pair, const Vector3& offset_S,
                                    const Vector3& sweep_S);

}  // namespace pd
