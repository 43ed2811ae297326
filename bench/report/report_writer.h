#pragma once
// The Markdown report of a run (pd_speed_error.md): machine, settings,
// targets with PASS/MISS, per-pair results, baselines, knob sweep, the
// paper's published timings and automatically found oddities.
#include <string>
#include <vector>

#include "bench/report/bench_results.h"

namespace pd_bench {

void WriteMarkdownReport(const BenchRun& run, const std::string& path,
                         const std::vector<std::string>& csv_files,
                         const std::vector<std::string>& png_files);

// The haptic scenario alone (bench_pd --haptic-only): pd_haptic.md.
void WriteHapticReport(const BenchRun& run, const std::string& path,
                       const std::vector<std::string>& csv_files,
                       const std::vector<std::string>& png_files);

}  // namespace pd_bench
