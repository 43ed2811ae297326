#pragma once
// PolyDepthOptions variations for the speed-against-error curve: one knob
// changed at a time from the defaults.
#include <string>
#include <vector>

#include "bench/report/bench_results.h"
#include "bench/common/progress.h"
#include "pd_core/polydepth/polydepth.h"

namespace pd_bench {

struct KnobConfig {
  std::string label;               // e.g. "max_iterations=4"
  pd::PolyDepthOptions options;
  bool coherent_scenarios = false; // run on path/shallow (else on random)
  bool is_default = false;         // same as the main run: reuse its answers
  // Random cases only: each pose solved this many more times after the
  // cold query, coherent (a probe held still; RunHeldPolyDepth).
  int held_queries = 0;
};

std::vector<KnobConfig> SweepConfigs();

// The swept knobs of random-configuration runs, and each one's default value
// written as in the configuration labels (so the defaults row joins each curve).
std::vector<std::pair<std::string, std::string>> SweptKnobDefaults();

// Number of Solve calls RunSweep will make for this pair (for progress bars).
int SweepWork(const PairResult& pair, const std::vector<KnobConfig>& configs, int sweep_cases);

// One row per (config, scenario) for this pair, all over the same cases: the
// reference cases plus `sweep_cases` colliding ones spread over the scenario
// (cold solves do not need the whole sequence). The default configuration's
// rows are the main run's answers on those cases.
std::vector<SweepRow> RunSweep(const PairResult& pair, const std::vector<KnobConfig>& configs,
                               int sweep_cases, Progress* progress);

}  // namespace pd_bench
