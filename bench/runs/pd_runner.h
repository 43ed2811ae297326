#pragma once
// Runs PolyDepth over a scenario's cases and checks every answer.
#include <vector>

#include "bench/report/bench_results.h"
#include "bench/common/progress.h"
#include "pd_core/polydepth/polydepth.h"

namespace pd_bench {

// Cold scenarios get a fresh solver per case (no state carried over);
// coherent ones one solver for the whole sequence, solved with
// coherent = true. Every case is solved (free path steps too, as a moving
// probe would be); out[i] answers cases[i].
std::vector<PdOutcome> RunPolyDepth(const BenchPair& pair, const std::vector<Case>& cases,
                                    const pd::PolyDepthOptions& options, bool coherent,
                                    Progress* progress);

}  // namespace pd_bench
