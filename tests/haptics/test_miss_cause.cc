// Deadline misses by cause (loop/miss_cause.h), tick by tick with made-up
// times: a 1 ms period, deadline at 1 ms after the scheduled start.
#include "haptics/loop/miss_cause.h"

#include <gtest/gtest.h>

namespace haptics {
namespace {

constexpr int64_t kPeriod = 1'000'000;

// A tick scheduled at 0 that woke `late_ns` late, ran `wall_ns` and used `cpu_ns`.
TickTimes Tick(int64_t late_ns, int64_t wall_ns, int64_t cpu_ns) {
  return {0, late_ns, late_ns + wall_ns, kPeriod, cpu_ns};
}

TEST(MissClassifier, TicksThatFitAreNotMisses) {
  MissClassifier c(kPeriod);
  EXPECT_EQ(c.Classify(Tick(0, 900'000, 900'000), -1), MissCause::kNone);
  EXPECT_EQ(c.Classify(Tick(50'000, 20'000, 20'000), 3), MissCause::kNone);
}

TEST(MissClassifier, LateWakeUpStalledAndComputeByTheTicksTimes) {
  MissClassifier c(kPeriod);
  // Woke 990 us late, ran 20 us: on time it would have fit.
  EXPECT_EQ(c.Classify(Tick(990'000, 20'000, 20'000), -1), MissCause::kLateWakeup);
  // On time, 1.5 ms of wall time of which 30 us CPU: not running (a stall).
  EXPECT_EQ(c.Classify(Tick(0, 1'500'000, 30'000), -1), MissCause::kStalled);
  // 1.5 ms of CPU, work not counted (geometry in line): compute.
  EXPECT_EQ(c.Classify(Tick(0, 1'500'000, 1'500'000), -1), MissCause::kCompute);
}

TEST(MissClassifier, AnOverrunOfWorkThatRanInHalfAPeriodIsChargedNotCompute) {
  MissClassifier c(kPeriod);
  // No witness yet: a counted tick that overran its CPU time is compute.
  EXPECT_EQ(c.Classify(Tick(0, 1'500'000, 1'500'000), 8), MissCause::kCompute);
  EXPECT_EQ(c.max_witness_work(), -1);
  // A tick of 8 terms that fit only just (600 us of CPU) is no witness.
  EXPECT_EQ(c.Classify(Tick(0, 600'000, 600'000), 8), MissCause::kNone);
  EXPECT_EQ(c.Classify(Tick(0, 1'500'000, 1'500'000), 8), MissCause::kCompute);
  // One that ran in 20 us is.
  EXPECT_EQ(c.Classify(Tick(0, 20'000, 20'000), 8), MissCause::kNone);
  EXPECT_EQ(c.max_witness_work(), 8);
  EXPECT_EQ(c.Classify(Tick(0, 1'500'000, 1'500'000), 8), MissCause::kCharged);
  EXPECT_EQ(c.Classify(Tick(0, 4'000'000, 4'000'000), 5), MissCause::kCharged);
  // More work than any witness: compute.
  EXPECT_EQ(c.Classify(Tick(0, 1'500'000, 1'500'000), 9), MissCause::kCompute);
  // A tick that queried in line is never excused by a witness.
  EXPECT_EQ(c.Classify(Tick(0, 1'500'000, 1'500'000), -1), MissCause::kCompute);
  // The stall and late wake-up rules come first.
  EXPECT_EQ(c.Classify(Tick(0, 1'500'000, 30'000), 9), MissCause::kStalled);
  EXPECT_EQ(c.Classify(Tick(990'000, 20'000, 20'000), 9), MissCause::kLateWakeup);
}

TEST(MissClassifier, AWitnessNeedsCountedWork) {
  MissClassifier c(kPeriod);
  // Ticks in line that ran fast say nothing about counted work.
  for (int i = 0; i < 10; ++i) EXPECT_EQ(c.Classify(Tick(0, 20'000, 20'000), -1), MissCause::kNone);
  EXPECT_EQ(c.max_witness_work(), -1);
  EXPECT_EQ(c.Classify(Tick(0, 1'500'000, 1'500'000), 0), MissCause::kCompute);
}

}  // namespace
}  // namespace haptics
