// The servo thread end to end without a network: poses in through the
// lock-free hand-over, wrenches out to a sink. Liveness and bookkeeping only;
// no timing is asserted (that belongs to benchmarks).
#include "haptics/servo_loop.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "haptics_test_util.h"

namespace haptics {
namespace {

class RecordingSink final : public WrenchSink {
 public:
  void Publish(const WrenchOutput& out) override {
    gaps += out.tick != last_tick + 1;
    last_tick = out.tick;
    nonfinite += !out.wrench.AllFinite();
    last_pose_seq = out.pose_seq;
    count.fetch_add(1);
  }
  std::atomic<int64_t> count{0};
  int64_t last_tick = 0, gaps = 0, nonfinite = 0, last_pose_seq = -1;
};

TEST(ServoLoop, RunsTicksAndReportsStatus) {
  const SceneConfig config = test::BoxOnBoxConfig();
  const SceneModels models = BuildSceneModels(config);
  HapticRenderer renderer(config, models);
  LatestValue<PoseSample> poses;
  RecordingSink sink;
  ServoLoopOptions options;
  options.rate_hz = 1000.0;
  options.realtime_priority = 0;  // do not ask in unit tests
  options.status_rate_hz = 10.0;
  ServoLoop loop(&renderer, &poses, &sink, options);
  loop.Start();
  int64_t seq = 0, statuses = 0;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (sink.count.load() < 300 && std::chrono::steady_clock::now() < give_up) {
    ++seq;
    poses.Write(test::MakePose(seq, Vector3(0, 0, 0.015 - 1e-5 * (seq % 1000))));
    if (const LoopStatus* s = loop.status().TakeNewest()) {
      ++statuses;
      EXPECT_GT(s->tick_count, 0);
      EXPECT_EQ(s->target_rate_hz, 1000.0);
      EXPECT_GT(s->compute_us.count, 0);
      EXPECT_LE(s->compute_us.p50, s->compute_us.max);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  loop.Stop();
  const LoopSummary summary = loop.Summary();
  ASSERT_GE(sink.count.load(), 300);
  EXPECT_EQ(summary.ticks, sink.count.load());
  EXPECT_EQ(sink.gaps, 0);
  EXPECT_EQ(sink.nonfinite, 0);
  EXPECT_GT(sink.last_pose_seq, 0);
  EXPECT_LE(sink.last_pose_seq, seq);
  EXPECT_GE(statuses, 1);
  EXPECT_GT(summary.elapsed_s, 0.0);
  EXPECT_GT(summary.compute_p99_us, 0.0);
  EXPECT_FALSE(summary.realtime);
  EXPECT_EQ(summary.renderer.poses_accepted + summary.renderer.poses_rejected.total() +
                summary.renderer.stale_ticks,
            summary.ticks);
  // Stop is idempotent.
  loop.Stop();
}

}  // namespace
}  // namespace haptics
