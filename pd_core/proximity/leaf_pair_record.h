#pragma once
// The leaf pairs a translational CCD descent visited with its boxes grown by
// a distance d: every leaf pair that can come within d of each other at any
// configuration of the swept segment before the first contact (past the part
// a candidate list showed contact-free, if it covered the start). PolyDepth
// localises at the CCD's landing point next; with the record it walks these
// pairs instead of descending both hierarchies again (a cold or uncovered
// warm iteration did one full descent for each: the localisation's half of
// its box tests).
#include <cstdint>
#include <vector>

#include "pd_core/geometry/pose.h"

namespace pd {

struct LeafPairRecord {
  struct LeafPair {
    int32_t ip, is;  // leaf node indices (probe BVH, scene BVH)
  };
  // Set by the caller before the CCD: how far apart recorded pairs may be (m).
  double distance = 0.0;
  std::vector<LeafPair> pairs;
  // The one configuration the record answers for (the CCD's landing point,
  // set by the caller); valid is false until then.
  Vector3 q_S = Vector3::Zero();
  bool valid = false;

  LeafPairRecord() { pairs.reserve(4096); }
  void Invalidate() { valid = false; }
  // True if the record holds every leaf pair that can come within `within`
  // (m) with the probe translated by any point of [q_a_S, q_b_S].
  bool Covers(const Vector3& q_a_S, const Vector3& q_b_S, double within) const {
    return valid && within <= distance && q_a_S == q_S && q_b_S == q_S;
  }
};

}  // namespace pd
