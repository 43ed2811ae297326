#pragma once
// The report's "Observations" section: oddities worth the solver author's
// attention (invalid answers, large errors, answers in free pockets, slow
// outliers, winning initializers), found in the run's data, not written by hand.
#include <ostream>

#include "bench/report/bench_results.h"

namespace pd_bench {

void WriteObservations(const BenchRun& run, std::ostream& md);

}  // namespace pd_bench
