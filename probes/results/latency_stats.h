#pragma once
// Summary statistics of round-trip latencies (µs). Percentiles use the
// nearest-rank definition: the smallest sample with at least p % of the
// samples at or below it, so p99 of 100 samples is the 99th smallest and
// every reported value is one that was actually measured.
#include <cstddef>
#include <vector>

namespace probes {

struct LatencySummary {
  size_t count = 0;
  double p50 = 0.0;   // all four are NaN when count == 0
  double p99 = 0.0;
  double max = 0.0;
  double mean = 0.0;
};

// p in [0, 100]; `sorted` ascending and non-empty (throws std::invalid_argument otherwise).
double NearestRankPercentile(const std::vector<double>& sorted, double p);

LatencySummary SummariseLatencies(std::vector<double> samples);

}  // namespace probes
