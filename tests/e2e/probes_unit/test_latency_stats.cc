// Latency statistics: nearest-rank percentiles, max, mean.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "probes/results/latency_stats.h"

namespace probes {
namespace {

TEST(LatencyStats, OneToHundred) {
  std::vector<double> v;
  for (int i = 100; i >= 1; --i) v.push_back(i);  // unsorted on purpose
  const LatencySummary s = SummariseLatencies(v);
  EXPECT_EQ(s.count, 100u);
  EXPECT_DOUBLE_EQ(s.p50, 50.0);
  EXPECT_DOUBLE_EQ(s.p99, 99.0);
  EXPECT_DOUBLE_EQ(s.max, 100.0);
  EXPECT_DOUBLE_EQ(s.mean, 50.5);
}

TEST(LatencyStats, SmallSetsUseMeasuredValues) {
  // Nearest rank of p50 over 4 samples is the 2nd; p99 is the 4th.
  const LatencySummary s = SummariseLatencies({40.0, 10.0, 30.0, 20.0});
  EXPECT_DOUBLE_EQ(s.p50, 20.0);
  EXPECT_DOUBLE_EQ(s.p99, 40.0);
  const LatencySummary one = SummariseLatencies({7.0});
  EXPECT_DOUBLE_EQ(one.p50, 7.0);
  EXPECT_DOUBLE_EQ(one.p99, 7.0);
  EXPECT_DOUBLE_EQ(one.max, 7.0);
}

TEST(LatencyStats, TailSampleShowsInP99) {
  // 1000 samples with ten at 5000: p99 (the 990th) must still be 100, p99.1 5000.
  std::vector<double> v(990, 100.0);
  v.insert(v.end(), 10, 5000.0);
  std::shuffle(v.begin(), v.end(), std::mt19937(3));
  std::vector<double> sorted = v;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_DOUBLE_EQ(SummariseLatencies(v).p99, 100.0);
  EXPECT_DOUBLE_EQ(NearestRankPercentile(sorted, 99.1), 5000.0);
  EXPECT_DOUBLE_EQ(SummariseLatencies(v).max, 5000.0);
}

TEST(LatencyStats, EmptyGivesNaN) {
  const LatencySummary s = SummariseLatencies({});
  EXPECT_EQ(s.count, 0u);
  EXPECT_TRUE(std::isnan(s.p50));
  EXPECT_TRUE(std::isnan(s.p99));
  EXPECT_TRUE(std::isnan(s.max));
  EXPECT_TRUE(std::isnan(s.mean));
}

TEST(LatencyStats, PercentileBoundsAndErrors) {
  const std::vector<double> sorted = {1.0, 2.0, 3.0};
  EXPECT_DOUBLE_EQ(NearestRankPercentile(sorted, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(NearestRankPercentile(sorted, 100.0), 3.0);
  EXPECT_THROW(NearestRankPercentile(sorted, 101.0), std::invalid_argument);
  EXPECT_THROW(NearestRankPercentile(sorted, -1.0), std::invalid_argument);
  EXPECT_THROW(NearestRankPercentile({}, 50.0), std::invalid_argument);
}

}  // namespace
}  // namespace probes
