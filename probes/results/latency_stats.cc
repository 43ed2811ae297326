#include "probes/results/latency_stats.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace probes {

double NearestRankPercentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) throw std::invalid_argument("NearestRankPercentile: no samples");
  if (!(p >= 0.0 && p <= 100.0)) throw std::invalid_argument("NearestRankPercentile: p not in [0, 100]");
  const double n = static_cast<double>(sorted.size());
  // Rank in 1..n; the small slack keeps p * n / 100 that is an integer in
  // exact arithmetic from rounding up by one ulp.
  const double rank = std::ceil(p / 100.0 * n - 1e-9);
  const size_t index = static_cast<size_t>(std::clamp(rank, 1.0, n)) - 1;
  return sorted[index];
}

LatencySummary SummariseLatencies(std::vector<double> samples) {
  LatencySummary s;
  s.count = samples.size();
  if (samples.empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    s.p50 = s.p99 = s.max = s.mean = nan;
    return s;
  }
  std::sort(samples.begin(), samples.end());
  s.p50 = NearestRankPercentile(samples, 50.0);
  s.p99 = NearestRankPercentile(samples, 99.0);
  s.max = samples.back();
  s.mean = std::accumulate(samples.begin(), samples.end(), 0.0) / static_cast<double>(s.count);
  return s;
}

}  // namespace probes
