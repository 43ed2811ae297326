#include "pd_core/polydepth/cold_starts.h"

#include <algorithm>

#include "pd_core/geometry/fibonacci_sphere.h"
#include "pd_core/proximity/mesh_collision.h"

namespace pd {

bool StartAbandon::Update(double norm) {
  if (last_ < 0.0) {
    last_ = norm;
    return false;
  }
  const double drop = last_ - norm;
  last_ = norm;
  if (drop <= 0.0) return false;  // the iteration itself stops on no progress
  bool stop = false;
  if (last_drop_ > 0.0) {
    // Geometric tail: the remaining descent is drop * r / (1 - r); r is
    // taken generously (at least 0.5, below 0.95) so slow starts continue.
    const double r = std::clamp(drop / last_drop_, 0.7, 0.95);
    const double limit = norm - drop * r / (1.0 - r);
    stop = limit > best_ * (1.0 + slack_);
  }
  last_drop_ = drop;
  return stop;
}

bool InnerProbeStarts(const ModelPair& pair, double best_norm, int num_directions,
                      std::initializer_list<double> fractions, int max_out,
                      std::vector<Vector3>* out_S, const std::function<bool()>& stop,
                      ProbeCursor* cursor) {
  ProbeCursor from_start;
  ProbeCursor& c = cursor != nullptr ? *cursor : from_start;
  const int num_fractions = static_cast<int>(fractions.size());
  for (; c.fraction < num_fractions; ++c.fraction, c.direction = 0) {
    const double f = fractions.begin()[c.fraction];
    for (; c.direction < num_directions; ++c.direction) {
      if (c.found >= max_out) return true;
      if (stop && stop()) return false;
      const Vector3 q = f * best_norm * FibonacciDirection(c.direction, num_directions);
      if (!InCollisionExpectingDepth(pair, q)) {
        out_S->push_back(q);
        ++c.found;
      }
    }
  }
  return true;
}

}  // namespace pd
