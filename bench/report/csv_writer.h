#pragma once
// CSV files of a run: one row per case, one per knob configuration, one per model.
#include <string>

#include "bench/report/bench_results.h"
#include "bench/runs/haptic_bench.h"

namespace pd_bench {

// Writes pd_cases.csv, pd_sweep.csv and pd_models.csv into dir; returns their names.
std::vector<std::string> WriteCsvFiles(const BenchRun& run, const std::string& dir);

// Writes pd_haptic.csv (one row per pose of every haptic path) into dir;
// returns its name.
std::string WriteHapticCsv(const std::vector<HapticPairResult>& runs, const std::string& dir);

// Writes pd_haptic_paths.csv (one row per haptic path of every pair, the
// first and the more seeded ones: colliding poses' times and work) into
// dir; returns its name.
std::string WriteHapticPathsCsv(const std::vector<HapticPairResult>& runs, const std::string& dir);

}  // namespace pd_bench
