#pragma once
// Order statistics for benchmark samples (times, errors). Percentiles use
// linear interpolation between closest ranks, so p50 of {1, 2} is 1.5.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
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

// A confidence interval (lo <= hi; NaN for an empty sample).
struct Interval {
  double lo = std::numeric_limits<double>::quiet_NaN();
  double hi = std::numeric_limits<double>::quiet_NaN();
};

// Percentile-bootstrap confidence interval of the mean of v: the means of
// `resamples` resamples of v (with replacement, each the size of v, drawn by
// a generator seeded with `seed`), cut at the (1 - level) / 2 and
// (1 + level) / 2 quantiles. The same sample gives the same interval. Why:
// a mean error over a few dozen reference cases is set by its few worst
// cases, so a point estimate alone overstates what a run shows. (From a
// skewed distribution at n ~ 24 the interval covers the true mean somewhat
// less often than `level`: 89% at 0.95 in tests/bench/test_bench_stats.cc.)
inline Interval BootstrapMeanInterval(const std::vector<double>& v, double level = 0.95,
                                      int resamples = 4000, uint64_t seed = 1) {
  Interval out;
  if (v.empty() || resamples < 1) return out;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<size_t> pick(0, v.size() - 1);
  std::vector<double> means(resamples);
  for (double& m : means) {
    double sum = 0.0;
    for (size_t i = 0; i < v.size(); ++i) sum += v[pick(rng)];
    m = sum / v.size();
  }
  out.lo = Percentile(means, 50.0 * (1.0 - level));
  out.hi = Percentile(means, 50.0 * (1.0 + level));
  return out;
}

inline std::vector<double> Abs(std::vector<double> v) {
  for (double& x : v) x = std::fabs(x);
  return v;
}

}  // namespace pd_bench
