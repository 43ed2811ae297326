#pragma once
// Exact translational continuous collision detection: the first time s in
// [0, 1] at which the probe, moved by offset_S + s * sweep_S, touches the
// scene surface. Exact per triangle pair (vertex-face, face-vertex and
// edge-edge events), no fixed step count.
#include "pd_core/proximity/leaf_pair_record.h"
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
//
// `record` (optional, not with s_stop): when the search descends the
// hierarchies, it also collects into record->pairs every leaf pair that can
// come within record->distance at a configuration of the sweep before the
// first contact (see leaf_pair_record.h), and returns with *record_complete
// true; otherwise (the leaf-pair list answered) the record is incomplete.
//
// `pair.stop_ccd` (optional): asked as the search goes (between the parts of
// a candidate-list walk and every 16 entries within one, before each pop of
// the descent); when it says stop,
// the search returns at once a fraction up to which the sweep is known
// contact-free (the parts of the list walked, the lowest pending key of the
// best-first descent, or an earlier contact found), with *stopped (if given)
// true. The record is then incomplete.
double FirstContactAlongTranslation(const ModelPair& pair, const Vector3& offset_S,
                                    const Vector3& sweep_S, double s_stop = -1.0,
                                    LeafPairRecord* record = nullptr,
                                    bool* record_complete = nullptr, bool* stopped = nullptr);

}  // namespace pd
