#pragma once
// Benchmarks one model pair: generates the scenarios, solves them with
// PolyDepth, runs the FCL baselines and the reference on subsets.
#include "bench/report/bench_results.h"

namespace pd_bench {

PairResult RunPair(const BenchPair& pair, const RunSettings& settings);

}  // namespace pd_bench
