#include "pd_core/polydepth/out_projection.h"

#include <algorithm>

#include "pd_core/proximity/translational_ccd.h"

namespace pd {

Vector3 OutProject(const ModelPair& pair, const Vector3& q_from, const Vector3& q_to, double margin,
                   bool* touched, double s_stop, bool* exact, LeafPairRecord* record) {
  const Vector3 d = q_to - q_from;
  const double len = d.norm();
  if (exact) *exact = true;
  if (record) record->Invalidate();
  if (len <= 0.0) {
    *touched = false;
    return q_to;
  }
  bool recorded = false, stopped = false;
  const double s =
      FirstContactAlongTranslation(pair, q_from, d, s_stop, record, &recorded, &stopped);
  if (s < 0) {
    *touched = false;
    if (record && recorded) {  // a free sweep's record holds the pairs near its end too
      record->q_S = q_to;
      record->valid = true;
    }
    return q_to;
  }
  // Stopped by the caller's budget (pair.stop_ccd): s is where the sweep is
  // known free, short of the contact; the point returned is free.
  *touched = true;
  if (exact) *exact = !stopped && s >= s_stop;
  const Vector3 q = q_from + std::max(0.0, s - margin / len) * d;
  if (record && recorded) {
    // Made at the contact (the sweep's pairs are complete there, past any
    // part a list showed free); it covers the landing point a margin back
    // as its distance has that room (Solve sets it).
    record->q_S = q_from + s * d;
    record->valid = true;
  }
  return q;
}

Vector3 OutProjectRecording(const ModelPair& pair, const Vector3& q_from, const Vector3& q_to,
                            double margin, bool* touched, LeafPairRecord* record) {
  return OutProject(pair, q_from, q_to, margin, touched, -1.0, nullptr, record);
}

}  // namespace pd
