#pragma once
// PolyDepth's cold start (no previous answer to follow): the early stop of
// a start that cannot beat the best verified answer, and probes from the
// inside for free configurations shallower than it.
#include <functional>
#include <initializer_list>
#include <vector>

#include "pd_core/proximity/model_pair.h"
namespace pd {

// Decides when a cold start's iteration cannot beat the best verified answer
// of the query. The iteration's |q| falls roughly geometrically; from its
// last two decrements the limit it converges to is extrapolated (with a
// safety factor on the ratio) and the start stops once even that limit is
// no better than the best answer. A heuristic bound, not a proof: `slack`
// (fraction) keeps starts that are close.
class StartAbandon {
 public:
  explicit StartAbandon(double best_norm, double slack = 0.1)
      : best_(best_norm), slack_(slack) {}
  // Call with |q| after each step (first call: the out-projected contact).
  // Returns true when the start should stop.
  bool Update(double norm);

 private:
  double best_, slack_;
  double last_ = -1.0, last_drop_ = -1.0;
};

// Where InnerProbeStarts stopped: the fraction and direction it probes
// next, and the free probes it has found.
struct ProbeCursor {
  int fraction = 0;
  int direction = 0;
  int found = 0;
};

// Free configurations shallower than the best answer so far: the probe
// moved by r * u for num_directions Fibonacci directions u and r = each of
// `fractions` of best_norm (m), in that order. Out-projected toward the
// query, each lands on the contact space below best_norm, also in a free
// pocket no outside start reaches (e.g. interlocked rings). The first
// max_out free ones are appended to *out_S. `stop`, if set, is asked before
// each probe's collision test; true ends the probing there (a bounded
// query's budget is spent: 256 shell probes cost about a third of a
// millisecond on 6k-triangle pairs) and returns false. With `cursor` the
// probing starts where the cursor says and leaves it where it stopped (a
// later call goes on from there). True once every direction is probed or
// max_out free ones are found.
bool InnerProbeStarts(const ModelPair& pair, double best_norm, int num_directions,
                      std::initializer_list<double> fractions, int max_out,
                      std::vector<Vector3>* out_S, const std::function<bool()>& stop = nullptr,
                      ProbeCursor* cursor = nullptr);

}  // namespace pd
