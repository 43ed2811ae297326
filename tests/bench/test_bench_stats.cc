// The benchmark's order statistics and the bootstrap interval of a mean
// (bench/common/stats.h), checked against values worked out by hand and
// against the known mean of a distribution (not against the routine itself).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "bench/common/stats.h"

namespace pd_bench {
namespace {

TEST(BenchStats, PercentileInterpolatesBetweenClosestRanks) {
  EXPECT_DOUBLE_EQ(Percentile({1.0, 2.0}, 50), 1.5);
  EXPECT_DOUBLE_EQ(Percentile({4.0, 1.0, 3.0, 2.0}, 0), 1.0);
  EXPECT_DOUBLE_EQ(Percentile({4.0, 1.0, 3.0, 2.0}, 100), 4.0);
  // Rank (5 - 1) * 0.9 = 3.6 between 4 and 5.
  EXPECT_DOUBLE_EQ(Percentile({5.0, 1.0, 4.0, 2.0, 3.0}, 90), 4.6);
  EXPECT_TRUE(std::isnan(Percentile({}, 50)));
}

TEST(BenchStats, BootstrapIntervalOfAnEmptySampleIsNaN) {
  const Interval ci = BootstrapMeanInterval({});
  EXPECT_TRUE(std::isnan(ci.lo));
  EXPECT_TRUE(std::isnan(ci.hi));
}

TEST(BenchStats, BootstrapIntervalOfAConstantSampleIsThatValue) {
  const Interval ci = BootstrapMeanInterval(std::vector<double>(24, 0.25));
  EXPECT_DOUBLE_EQ(ci.lo, 0.25);
  EXPECT_DOUBLE_EQ(ci.hi, 0.25);
}

TEST(BenchStats, BootstrapIntervalIsDeterministicAndHoldsTheMean) {
  const std::vector<double> v = {0.1, 0.0, 0.3, 0.2, 8.2, 0.0, 0.4, 0.1, 0.0, 0.6, 0.2, 0.1};
  const Interval a = BootstrapMeanInterval(v), b = BootstrapMeanInterval(v);
  EXPECT_EQ(a.lo, b.lo);
  EXPECT_EQ(a.hi, b.hi);
  const double mean = 10.2 / 12.0;
  EXPECT_LT(a.lo, mean);
  EXPECT_GT(a.hi, mean);
  // One outlier of twelve sets the mean: resamples without it average
  // about 0.19, so the interval reaches down near there; with it twice
  // or more, well above the sample mean.
  EXPECT_LT(a.lo, 0.3);
  EXPECT_GT(a.hi, 1.5);
  // A wider level gives a wider interval.
  const Interval wide = BootstrapMeanInterval(v, 0.99);
  EXPECT_LE(wide.lo, a.lo);
  EXPECT_GE(wide.hi, a.hi);
}

// Coverage: samples of 24 from an exponential distribution of mean 1 (as
// skewed as the benchmark's errors); the 95% interval holds the true mean
// in about 90-95% of samples (the percentile bootstrap under-covers a
// little at this size). An interval that ignored the spread, or cut at the
// wrong percentiles, would be far off.
TEST(BenchStats, BootstrapIntervalCoversTheTrueMean) {
  std::mt19937_64 rng(7);
  std::exponential_distribution<double> draw(1.0);
  constexpr int kTrials = 400;
  int covered = 0;
  double width = 0.0;
  for (int t = 0; t < kTrials; ++t) {
    std::vector<double> v(24);
    for (double& x : v) x = draw(rng);
    const Interval ci = BootstrapMeanInterval(v, 0.95, 1000, t + 1);
    covered += ci.lo <= 1.0 && 1.0 <= ci.hi;
    width += ci.hi - ci.lo;
  }
  EXPECT_GE(covered, 0.86 * kTrials);
  EXPECT_LE(covered, 0.99 * kTrials);
  // Normal theory: 2 * 1.96 * sigma / sqrt(24) = 0.80 for sigma = 1.
  EXPECT_NEAR(width / kTrials, 0.80, 0.12);
}

}  // namespace
}  // namespace pd_bench
