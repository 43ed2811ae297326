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

// A probe held still after a cold query: each case solved cold on a fresh
// solver, then `held_queries` more times at the same pose, coherent (a
// bounded cold query's follow-up goes on in them: PolyDepthOptions::
// max_time_us). out[i] is the last answer, checked, with the time and
// work of all the case's queries.
std::vector<PdOutcome> RunHeldPolyDepth(const BenchPair& pair, const std::vector<Case>& cases,
                                        const pd::PolyDepthOptions& options, int held_queries,
                                        Progress* progress);

}  // namespace pd_bench
