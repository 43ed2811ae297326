#pragma once
// PNG plots of a run through gnuplot: the knob sweep's time against error per
// pair, and the solve-time distributions per pair and scenario. The gnuplot
// script (with its data inline) is kept beside the PNGs.
#include <string>
#include <vector>

#include "bench/report/bench_results.h"

namespace pd_bench {

// Returns the PNG file names written; empty (and a message on stderr) if
// gnuplot is missing or fails.
std::vector<std::string> WritePlots(const BenchRun& run, const std::string& dir);

}  // namespace pd_bench
