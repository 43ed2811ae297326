#pragma once
// Order statistics for benchmark samples (times, errors). Percentiles use
// linear interpolation between closest ranks, so p50 of {1, 2} is 1.5.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace pd_bench {

inline double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const double pos = std::clamp(p, 0.0, 100.0) / 100.0 * (v.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(pos));
  const size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - lo) * (v[hi] - v[lo]);
}

inline double Mean(const std::vector<double>& v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  double s = 0.0;
  for (double x : v) s += x;
  return s / v.size();
}

inline double Max(const std::vector<double>& v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  return *std::max_element(v.begin(), v.end());
}

struct Summary {
  int n = 0;
  double mean = std::numeric_limits<double>::quiet_NaN();
  double median = mean, p90 = mean, p95 = mean, p99 = mean, max = mean;
};

inline Summary Summarize(const std::vector<double>& v) {
  Summary s;
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  s.mean = Mean(v);
  s.median = Percentile(v, 50);
  s.p90 = Percentile(v, 90);
  s.p95 = Percentile(v, 95);
  s.p99 = Percentile(v, 99);
  s.max = Max(v);
  return s;
}

inline std::vector<double> Abs(std::vector<double> v) {
  for (double& x : v) x = std::fabs(x);
  return v;
}

}  // namespace pd_bench
