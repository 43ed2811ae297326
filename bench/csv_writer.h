#pragma once
// CSV files of a run: one row per case, one per knob configuration, one per model.
#include <string>

#include "bench/bench_results.h"

namespace pd_bench {

// Writes pd_cases.csv, pd_sweep.csv and pd_models.csv into dir; returns their names.
std::vector<std::string> WriteCsvFiles(const BenchRun& run, const std::string& dir);

}  // namespace pd_bench
