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
//
// `s_stop` (optional): the caller only needs the first contact when it is at
// s >= s_stop (e.g. ranking starts by where they land: one that touches
// earlier is out of the running). Once a contact before s_stop is found the
// search returns it at once: a result below s_stop is a contact, an upper
// bound on the first one. A result at or above s_stop is exact.
double FirstContactAlongTranslation(const ModelPair& pair, const Vector3& offset_S,
                                    const Vector3& sweep_S, double s_stop = -1.0);

}  // namespace pd
