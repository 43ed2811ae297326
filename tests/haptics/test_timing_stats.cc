#include "haptics/loop/timing_stats.h"

#include <gtest/gtest.h>

namespace haptics {
namespace {

TEST(SampleWindow, NearestRankPercentilesOfTheLastSamples) {
  SampleWindow w(100);
  EXPECT_EQ(w.Summarize().count, 0);
  for (int i = 1; i <= 250; ++i) w.Add(i);  // keeps 151..250
  const TimingSummary s = w.Summarize();
  EXPECT_EQ(s.count, 100);
  EXPECT_EQ(s.p50, 200.0);
  EXPECT_EQ(s.p99, 249.0);
  EXPECT_EQ(s.max, 250.0);
  w.Clear();
  w.Add(7.0);
  const TimingSummary one = w.Summarize();
  EXPECT_EQ(one.count, 1);
  EXPECT_EQ(one.p50, 7.0);
  EXPECT_EQ(one.p99, 7.0);
}

TEST(DurationHistogram, PercentilesToOneMicrosecond) {
  DurationHistogram h(1000);
  for (int i = 0; i < 990; ++i) h.Add(10.4);
  for (int i = 0; i < 10; ++i) h.Add(500.2);
  EXPECT_EQ(h.count(), 1000);
  EXPECT_EQ(h.Percentile(0.5), 11.0);   // upper edge of the [10, 11) bin
  EXPECT_EQ(h.Percentile(0.99), 11.0);
  EXPECT_EQ(h.Percentile(0.995), 500.2);  // capped at the max seen
  h.Add(5000.0);  // overflow
  EXPECT_EQ(h.max(), 5000.0);
  EXPECT_EQ(h.Percentile(1.0), 5000.0);
}

}  // namespace
}  // namespace haptics
