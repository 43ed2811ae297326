// TickLog, the preallocated per-tick record behind haptic_server
// --timing-log, and its use by the servo loop. No timing is asserted.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "alloc_counter.h"
#include "haptics/loop/servo_loop.h"
#include "haptics/loop/timing_stats.h"
#include "haptics_test_util.h"

namespace haptics {
namespace {

TickRecord Record(float period_us, float compute_us, int32_t contacts, int32_t flags, bool missed) {
  TickRecord r;
  r.period_us = period_us;
  r.compute_us = compute_us;
  r.contact_count = contacts;
  r.flags = flags;
  r.missed = missed;
  return r;
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(TickLog, KeepsRecordsUpToCapacityAndCountsTheRest) {
  TickLog log(3);
  EXPECT_EQ(log.capacity(), 3u);
  for (int i = 0; i < 5; ++i) log.Add(Record(1000.0f + i, 10.0f * i, i, 0, i == 4));
  ASSERT_EQ(log.size(), 3u);
  EXPECT_EQ(log.not_logged(), 2);
  // The first three are kept, unchanged by the overflow.
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(log[i].period_us, 1000.0f + i);
    EXPECT_EQ(log[i].compute_us, 10.0f * i);
    EXPECT_EQ(log[i].contact_count, i);
    EXPECT_FALSE(log[i].missed);
  }
}

TEST(TickLog, AddDoesNotAllocate) {
  TickLog log(1000);
  const int64_t before = test::ThreadAllocations();
  for (int i = 0; i < 2000; ++i) log.Add(Record(1000.0f, 50.0f, 1, 0, false));
  EXPECT_EQ(test::ThreadAllocations(), before);
  EXPECT_EQ(log.size(), 1000u);
  EXPECT_EQ(log.not_logged(), 1000);
}

TEST(TickLog, WritesCsvWithHeaderAndRows) {
  TickLog log(4);
  log.Add(Record(0.0f, 12.5f, 0, 0, false));
  log.Add(Record(1003.25f, 1500.0f, 2, 65, true));
  log.Add(Record(997.0f, 8.0f, 1, 16, false));
  const std::string path = ::testing::TempDir() + "/tick_log_test.csv";
  std::string error;
  ASSERT_TRUE(log.WriteCsv(path, 1000.0, &error)) << error;
  EXPECT_EQ(ReadFile(path),
            "# nominal_period_us=1000.000 ticks_logged=3 ticks_not_logged=0\n"
            "tick,period_us,compute_us,contact_count,flags,missed\n"
            "0,0.000,12.500,0,0,0\n"
            "1,1003.250,1500.000,2,65,1\n"
            "2,997.000,8.000,1,16,0\n");
  std::remove(path.c_str());
}

TEST(TickLog, UnwritablePathIsAnErrorNamingIt) {
  TickLog log(1);
  log.Add(Record(1000.0f, 1.0f, 0, 0, false));
  const std::string path = ::testing::TempDir() + "/no_such_dir_for_tick_log/x.csv";
  std::string error;
  EXPECT_FALSE(log.WriteCsv(path, 1000.0, &error));
  EXPECT_NE(error.find(path), std::string::npos) << error;
}

TEST(TickLog, ServoLoopLogsEveryTick) {
  const SceneConfig config = test::BoxOnBoxConfig();
  const SceneModels models = BuildSceneModels(config);
  HapticRenderer renderer(config, models);
  LatestValue<PoseSample> poses;
  struct CountingSink final : WrenchSink {
    void Publish(const WrenchOutput&) override { ++count; }
    std::atomic<int64_t> count{0};
  } sink;
  TickLog log(100000);
  ServoLoopOptions options;
  options.realtime_priority = 0;
  options.tick_log = &log;
  ServoLoop loop(&renderer, &poses, &sink, options);
  loop.Start();
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  int64_t seq = 0;
  while (sink.count.load() < 200 && std::chrono::steady_clock::now() < give_up) {
    // Tool origin 5 mm below the table top: in contact once the tool gets there.
    poses.Write(test::MakePose(++seq, Vector3(0, 0, 0.005)));
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  loop.Stop();
  const LoopSummary summary = loop.Summary();
  ASSERT_GE(summary.ticks, 200);
  ASSERT_EQ(static_cast<int64_t>(log.size()), summary.ticks);
  EXPECT_EQ(log.not_logged(), 0);
  EXPECT_EQ(log[0].period_us, 0.0f);  // no previous wake-up
  int64_t misses = 0, in_contact = 0;
  for (size_t i = 0; i < log.size(); ++i) {
    if (i > 0) EXPECT_GT(log[i].period_us, 0.0f) << "tick " << i;
    EXPECT_GT(log[i].compute_us, 0.0f) << "tick " << i;
    misses += log[i].missed;
    in_contact += log[i].contact_count > 0;
  }
  EXPECT_EQ(misses, summary.deadline_misses);
  EXPECT_GT(in_contact, 0);
}

}  // namespace
}  // namespace haptics
