#pragma once
// Out-projection, the move of PolyDepth's search along a translation: from a
// free configuration toward a target, the last free point before the first
// contact (translational CCD, translational_ccd.h). Translations q_S of the
// probe in the scene frame S, from the query pose (m).
#include "pd_core/geometry/pose.h"
#include "pd_core/proximity/leaf_pair_record.h"
#include "pd_core/proximity/model_pair.h"

namespace pd {

// Out-projection: from a free q_from toward q_to, the last free point before
// first contact, backed off by `margin` (m) along the motion. Returns q_to if
// the whole segment is free. *touched tells which. With `s_stop` (see
// FirstContactAlongTranslation) a contact found before it ends the search:
// *exact (if given) is false then, and the point returned lies before the
// exact one. With `record` (not with s_stop), the CCD records the leaf pairs
// near the sweep and the record answers for the point returned if touching
// (the localisation there follows; see leaf_pair_record.h).
Vector3 OutProject(const ModelPair& pair, const Vector3& q_from, const Vector3& q_to, double margin,
                   bool* touched, double s_stop = -1.0, bool* exact = nullptr,
                   LeafPairRecord* record = nullptr);

// OutProject recording the leaf pairs near its landing point.
Vector3 OutProjectRecording(const ModelPair& pair, const Vector3& q_from, const Vector3& q_to,
                            double margin, bool* touched, LeafPairRecord* record);

}  // namespace pd
