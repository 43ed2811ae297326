#pragma once
// What a convex-pair PD routine (closed form or GJK/EPA) returns before the
// dispatcher turns it into a PenetrationResult. World frame W, metres.
#include "pd_core/geometry/pose.h"

namespace pd {

struct PairPdAnswer {
  bool in_collision = false;   // interiors overlap (touching is free)
  double depth = 0.0;          // PD (m), exact for closed forms; GJK/EPA: an
                               // upper bound within the EPA tolerance
  Vector3 normal_W = Vector3::Zero();  // unit direction the probe moves out
  int iterations = 0;          // GJK + EPA iterations (0 for closed forms)
  bool converged = true;       // false: EPA hit its cap, answer from the fallback
};

}  // namespace pd
