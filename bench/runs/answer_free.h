#pragma once
// The benchmarks' freedom check of a PD answer: the probe moved by it is
// free, and still free kHapticFreeMargin of the pair's size further out
// along it (not resting in a thin free pocket).
#include "bench/report/bench_results.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"

namespace pd_bench {

// The probe moved kHapticFreeMargin x size further out along q_S (its
// translation, in S) is free; q_S itself is the caller's test.
inline bool FreeFurtherAlong(const pd::ModelPair& mp, const pd::Vector3& q_S) {
  const double n = q_S.norm();
  return n == 0 || !pd::InCollision(mp, q_S * (1.0 + kHapticFreeMargin * mp.size() / n));
}

// q_S is free, and free further out along itself (FreeFurtherAlong).
inline bool AnswerFreeBeyond(const pd::ModelPair& mp, const pd::Vector3& q_S) {
  return !pd::InCollision(mp, q_S) && FreeFurtherAlong(mp, q_S);
}

}  // namespace pd_bench
