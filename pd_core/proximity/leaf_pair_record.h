#pragma once
// The leaf pairs a translational CCD descent visited with its boxes grown by
// a distance d: every leaf pair that can come within d of each other at any
// configuration of the swept segment before the first contact (past the part
// a candidate list showed contact-free, if it covered the start). PolyDepth
// localises at the CCD's landing point next; with the record it walks these
// pairs instead of descending both hierarchies again (a cold or uncovered
// warm iteration did one full descent for each: the localisation's half of
// its box tests). A localisation that had to find its pairs itself records
// them the same way (contact_constraints.h), and the collision tests just
// off that configuration (an answer's verification and pocket tests) walk
// them.
#include <algorithm>
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
  // The configuration the record was made at (the CCD's landing point, set
  // by the caller, or a localisation's configuration); valid is false until
  // then.
  Vector3 q_S = Vector3::Zero();
  bool valid = false;

  LeafPairRecord() { pairs.reserve(4096); }
  void Invalidate() { valid = false; }
  // True if the record holds every leaf pair that can come within `within`
  // (m) with the probe translated by any point of [q_a_S, q_b_S]. Moving the
  // probe by r brings no two boxes nearer than r, so a pair within `within`
  // at a point r from q_S is within within + r at q_S: the record answers
  // for a ball around q_S (and for a segment inside it: the ball is convex).
  // It lets the checks just off an answer (its verification, the pocket
  // tests) walk the pairs its localisation found instead of descending.
  bool Covers(const Vector3& q_a_S, const Vector3& q_b_S, double within) const {
    if (!valid || within > distance) return false;
    const double r = std::max((q_a_S - q_S).norm(), (q_b_S - q_S).norm());
    return within + r <= distance;
  }
};

}  // namespace pd
