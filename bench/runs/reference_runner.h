#pragma once
// Runs the slow reference PD (pd::ReferencePenetrationDepth) on a subset of
// cases, on several threads: the reference is far too slow for every case.
#include <vector>

#include "bench/report/bench_results.h"
#include "bench/common/progress.h"
#include "pd_core/reference/reference_pd.h"

namespace pd_bench {

struct RefJob {
  const Case* c;
  pd::Vector3 pd_translation_W;  // PolyDepth's answer, checked independently
  RefOutcome* out;
};

void RunReference(const BenchPair& pair, const std::vector<RefJob>& jobs,
                  const pd::ReferencePdOptions& options, int threads, Progress* progress);

// The same with the run's reference settings (directions, refinement, threads):
// the haptic scenario's directions and refinement if `haptic`.
void RunReference(const BenchPair& pair, const std::vector<RefJob>& jobs, const RunSettings& st,
                  Progress* progress, bool haptic = false);

// `k` indices spread evenly over [0, n) (all of them if k >= n).
std::vector<int> SpreadIndices(int n, int k);

}  // namespace pd_bench
