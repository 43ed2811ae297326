// The servo tick never waits for the geometry (issue 11): PD on its own
// thread (geometry_thread.h), the tick rendering the local contact model.
//  - the worker answers the newest posted pose only;
//  - a geometry whose every query takes 20 ms (a cold PolyDepth query on real
//    meshes, here a geometry thread slowed down on purpose) still gets a
//    wrench every tick: no gap between wrenches near the query time;
//  - no energy gain over a press, hold and release cycle with the geometry
//    answering at 50 Hz, 20 ms late;
//  - the model ages out (contact ramps to zero, flagged) when the geometry
//    thread stops.
// Bookkeeping and physics are asserted; the only time bounds are gross (a
// wrench gap below the 20 ms the query takes).
#include "haptics/contact/geometry_thread.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

#include "haptics/haptic_renderer.h"
#include "haptics/loop/servo_loop.h"
#include "alloc_counter.h"
#include "haptics/io/wrench_output.h"
#include "haptics_test_util.h"
#include "haptics/scene/load_scene_config.h"
#include "tests/prerequisites.h"

namespace haptics {
namespace {

using Clock = std::chrono::steady_clock;

SceneConfig ThreadedBoxOnBox() {
  SceneConfig c = test::BoxOnBoxConfig();
  c.contact.geometry_thread = GeometryThreadMode::kOn;
  return c;
}

// A box-on-box renderer whose ticks render the worker's answers; the test
// drives the worker (RunOnce) on its own thread.
struct AsyncBoxOnBox {
  SceneConfig config = ThreadedBoxOnBox();
  SceneModels models = BuildSceneModels(config);
  HapticRenderer renderer{config, models};
  AsyncBoxOnBox() { renderer.set_geometry_worker_running(true); }
};

TEST(GeometryWorker, AnswersTheNewestPoseOnly) {
  const SceneConfig config = ThreadedBoxOnBox();
  const SceneModels models = BuildSceneModels(config);
  ContactGeometry geometry(models.tool, models.X_TG, models.objects, config.contact);
  GeometryWorker worker(&geometry);
  EXPECT_TRUE(worker.idle());
  EXPECT_FALSE(worker.RunOnce());
  EXPECT_EQ(worker.TakeAnswer(), nullptr);
  for (int64_t tick = 1; tick <= 3; ++tick) {
    Isometry3 X = Isometry3::Identity();
    X.translation() = Vector3(0, 0, 0.01 - 0.001 * tick);
    worker.Post(X, tick);
  }
  EXPECT_FALSE(worker.idle());
  EXPECT_TRUE(worker.RunOnce());
  EXPECT_TRUE(worker.idle());
  EXPECT_FALSE(worker.RunOnce());
  const ContactSnapshot* answer = worker.TakeAnswer();
  ASSERT_NE(answer, nullptr);
  EXPECT_EQ(answer->request_tick, 3);
  ASSERT_EQ(answer->num_pairs, 1);
  EXPECT_EQ(answer->pairs[0].status, PairContactModel::Status::kContact);
  EXPECT_NEAR(answer->pairs[0].depth, 0.003, 1e-9);
  EXPECT_EQ(worker.TakeAnswer(), nullptr);
  EXPECT_EQ(worker.queries(), 1);
}

// The tick's counted work (HapticRenderer::tick_work), which tells an
// overrun of the tick's own work from time the platform charged to the
// thread (miss_cause.h): the contact model terms when the tick renders the
// worker's answer, more in contact than free; -1 (not counted) in line.
TEST(GeometryWorker, TicksRenderingTheWorkersAnswerCountTheirModelTerms) {
  AsyncBoxOnBox box;
  HapticRenderer& renderer = box.renderer;
  ASSERT_TRUE(renderer.geometry_async());
  double t = 0.0;
  int64_t seq = 0;
  renderer.Tick(t, nullptr);
  EXPECT_EQ(renderer.tick_work(), 0);  // not engaged: nothing evaluated
  // 100 rounds (the coupled tool follows the device), each a tick that posts
  // the pose and one that takes the worker's answer.
  auto settle_at = [&](double z) {
    for (int i = 0; i < 100; ++i) {
      const PoseSample pose = test::MakePose(++seq, Vector3(0, 0, z));
      renderer.Tick(t += renderer.dt(), &pose);
      renderer.geometry_worker().RunOnce();
      renderer.Tick(t += renderer.dt(), &pose);
    }
    return renderer.tick_work();
  };
  const int64_t contact_work = settle_at(0.007);  // 3 mm into the table
  ASSERT_GT(renderer.contact().num_in_contact, 0);
  const int64_t free_work = settle_at(0.03);      // 2 cm above it
  ASSERT_EQ(renderer.contact().num_in_contact, 0);
  EXPECT_GE(free_work, 0);
  EXPECT_GE(contact_work, 2);  // the pair taken and evaluated, and its regions
  EXPECT_GT(contact_work, free_work);
  renderer.set_geometry_worker_running(false);

  SceneConfig sync_config = box.config;
  sync_config.contact.geometry_thread = GeometryThreadMode::kOff;
  HapticRenderer sync(sync_config, box.models);
  const PoseSample pose = test::MakePose(1, Vector3(0, 0, 0.007));
  sync.Tick(0.0, &pose);
  EXPECT_EQ(sync.tick_work(), -1);
}

// Neither hot loop allocates once warm: the servo tick with the geometry on
// the worker (post, take the answer, evaluate the model) and the worker's
// query (driven here on the same thread, every third tick, so both count).
TEST(GeometryWorker, NeitherLoopAllocatesAfterWarmUp) {
  AsyncBoxOnBox box;
  HapticRenderer& renderer = box.renderer;
  ASSERT_TRUE(renderer.geometry_async());
  double t = 0.0;
  int64_t seq = 0;
  auto run = [&] {
    for (int i = 0; i < 300; ++i) {
      const Quaternion q(Eigen::AngleAxisd(0.002 * i, Vector3(1, 1, 0).normalized()));
      const PoseSample pose = test::MakePose(++seq, Vector3(0.0001 * i, 0, 0.02 - 0.0001 * i), q);
      renderer.Tick(t, &pose);
      t += renderer.dt();
      if (i % 3 == 0) renderer.geometry_worker().RunOnce();
    }
  };
  run();
  const int64_t before = test::ThreadAllocations();
  run();
  EXPECT_EQ(test::ThreadAllocations() - before, 0);
  EXPECT_GT(renderer.counts().model_updates, 150);
  EXPECT_GT(renderer.contact().num_in_contact, 0);
  renderer.set_geometry_worker_running(false);
}

class TimedSink final : public WrenchSink {
 public:
  explicit TimedSink(size_t capacity) : times_ns(capacity), force_z(capacity) {}
  void Publish(const WrenchOutput& out) override {
    gaps += out.tick != last_tick + 1;
    last_tick = out.tick;
    if (n < times_ns.size()) {
      times_ns[n] = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
      force_z[n] = out.wrench.f_W.z();
      ++n;
    }
    count.fetch_add(1);
  }
  std::vector<int64_t> times_ns;
  std::vector<double> force_z;
  size_t n = 0;
  int64_t last_tick = 0, gaps = 0;
  std::atomic<int64_t> count{0};
};

TEST(GeometryThread, QueriesOf20msStillGetAWrenchEveryTick) {
  const SceneConfig config = ThreadedBoxOnBox();
  const SceneModels models = BuildSceneModels(config);
  HapticRenderer renderer(config, models);
  LatestValue<PoseSample> poses;
  TimedSink sink(4000);
  ServoLoopOptions options;
  options.realtime_priority = 0;
  options.geometry.min_query_time_s = 0.020;
  ServoLoop loop(&renderer, &poses, &sink, options);
  loop.Start();
  // Press 3 mm into the table for 0.8 s.
  int64_t seq = 0;
  const auto end = Clock::now() + std::chrono::milliseconds(800);
  while (Clock::now() < end) {
    poses.Write(test::MakePose(++seq, Vector3(0, 0, 0.007)));
    std::this_thread::sleep_for(std::chrono::microseconds(1000));
  }
  loop.Stop();
  const LoopSummary s = loop.Summary();
  ASSERT_TRUE(s.geometry_thread);
  EXPECT_EQ(sink.gaps, 0);
  ASSERT_GT(sink.n, 300u);
  // Wrenches kept coming while each query took 20 ms: the tick never waited.
  // A tick that waited would leave a gap of 15 ms or more at every answer
  // (tens of them); a loaded machine may stall an unprivileged thread now
  // and then, so a few are tolerated.
  int gaps_15ms = 0;
  for (size_t i = 1; i < sink.n; ++i) gaps_15ms += sink.times_ns[i] - sink.times_ns[i - 1] >= 15'000'000;
  EXPECT_LE(gaps_15ms, 3) << "wrenches waited for the 20 ms queries";
  EXPECT_GT(s.renderer.geometry_async_ticks, 300);
  // About 50 answers per second, each about 20 ticks old when it arrived.
  EXPECT_GE(s.renderer.model_updates, 10);
  EXPECT_LE(s.renderer.model_updates, 60);
  EXPECT_GE(s.model_age_max_ticks, 19);
  // The tool is held on the table: the device feels the table (upward force).
  EXPECT_GT(sink.force_z[sink.n - 1], 1.0);
  EXPECT_EQ(s.renderer.limiter.nonfinite, 0);
}

// The same on a real mesh scene whose cold queries really take 4 ms or more:
// CGAL knot1 (6.4k triangles, 5 cm) on the refined elephant
// (89k triangles; bench/scenes/knot_tool_elephant_bunny_164k.yaml without the
// bunny), PolyDepth with no time budget and no warm start (every query
// cold: the 7 mm jumps below were warm queries of 6-15 ms at c86ceb8, under
// 2 ms at the CCD's descent cut). The device jumps 7 mm along the
// elephant's back every 150 ms. The test measures the queries' times
// (worker, polled) and asserts the longest took at least kSlowQuery: if
// PolyDepth gets that fast here, pick a harder scene.
TEST(GeometryThread, RealMeshColdQueriesOfManyMsStillGetAWrenchEveryTick) {
  PD_REQUIRE_FILE(test::MeshDir() + "/refined_elephant.off", "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(test::MeshDir() + "/knot1.off", "run scripts/fetch_meshes.sh");
  SceneConfig config = LoadSceneConfig(test::BenchSceneDir() + "/knot_tool_elephant_bunny_164k.yaml");
  ASSERT_EQ(config.objects[0].name, "elephant");
  config.objects.resize(1);
  config.contact.geometry_thread = GeometryThreadMode::kOn;
  config.contact.geometry_budget_s = 10.0;  // queries run to convergence
  config.servo.soft_engage_s = 0.0;
  const SceneModels models = BuildSceneModels(config);
  pd::PolyDepthOptions cold;
  cold.warm_start = false;
  HapticRenderer renderer(config, models, cold);
  LatestValue<PoseSample> poses;
  TimedSink sink(4000);
  ServoLoopOptions options;
  options.realtime_priority = 0;
  ServoLoop loop(&renderer, &poses, &sink, options);
  loop.Start();
  // About 1 mm into the elephant's back, at two spots 7 mm apart.
  const Vector3 p_A(-0.024, -0.004, 0.0185), p_B(-0.024, 0.003, 0.0185);
  int64_t seq = 0;
  double max_query_us = 0.0;
  const auto start = Clock::now();
  for (auto now = start; now < start + std::chrono::milliseconds(1200); now = Clock::now()) {
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now - start).count();
    poses.Write(test::MakePose(++seq, (ms / 150) % 2 == 0 ? p_A : p_B));
    max_query_us = std::max(max_query_us, renderer.geometry_worker().last_query_us());
    std::this_thread::sleep_for(std::chrono::microseconds(1000));
  }
  loop.Stop();
  const LoopSummary s = loop.Summary();
  ASSERT_TRUE(s.geometry_thread);
  std::printf("longest query %.1f ms, %ld answers, %zu wrenches\n", max_query_us * 1e-3,
              static_cast<long>(s.renderer.model_updates), sink.n);
  // The scene is what the test claims: its cold queries take 4 ms or more.
  constexpr double kSlowQuery_us = 4'000.0;
  EXPECT_GE(max_query_us, kSlowQuery_us);
  EXPECT_EQ(sink.gaps, 0);
  ASSERT_GT(sink.n, 500u);
  // No tick ran a query itself: a tick's CPU time stays far below a slow
  // query's. The 99th percentile, not the max: on this VM a vCPU stolen
  // while the thread is current is charged to it, and CI saw one tick of
  // 2.1 ms CPU time here. Ticks that ran the ~240 queries (4 ms or more
  // each) would put about a fifth of the 1200 ticks above 1 ms.
  EXPECT_LT(s.tick_cpu_p99_us, 1000.0);
  // Wrenches kept coming while the queries ran: a tick that waited would
  // leave a gap about as long as a slow query at every cold answer (8
  // jumps). A loaded machine stalls an unprivileged thread now and then:
  // with two CPU hogs on this 2-core machine, gaps of up to 7.4 ms beside
  // queries of 13-32 ms (a 4 ms threshold counted 3-7 of them).
  int long_gaps = 0;
  for (size_t i = 1; i < sink.n; ++i)
    long_gaps += sink.times_ns[i] - sink.times_ns[i - 1] >= 0.75 * max_query_us * 1e3;
  EXPECT_LE(long_gaps, 2) << "wrenches waited for the cold queries (longest " << max_query_us << " us)";
  EXPECT_GE(s.renderer.model_updates, 8);
  // The tool is on the elephant: the device feels it push up.
  double max_up = 0.0;
  for (size_t i = 0; i < sink.n; ++i) max_up = std::max(max_up, sink.force_z[i]);
  EXPECT_GT(max_up, 0.5);
  EXPECT_EQ(s.renderer.limiter.nonfinite, 0);
}

// Ticks the renderer at real time (1 ms) along a device path; returns the
// work the rendered force did on the hand, sum f · dp (J): positive is
// energy the haptic loop made up.
struct PressCycle {
  double work = 0.0;
  double peak_force = 0.0;
  int32_t flags_seen = 0;
  int64_t ticks = 0;
};

PressCycle RunPressCycle(HapticRenderer* renderer, bool pace) {
  // Tool bottom at z = 0 when its centre is at 0.01: from 5 mm above, down
  // to 6 mm deep in 300 ms, hold 300 ms, back up in 300 ms, rest 100 ms.
  auto z_at = [](int i) {
    const double top = 0.015, bottom = 0.004;
    if (i < 300) return top + (bottom - top) * i / 300.0;
    if (i < 600) return bottom;
    if (i < 900) return bottom + (top - bottom) * (i - 600) / 300.0;
    return top;
  };
  PressCycle cycle;
  const auto start = Clock::now();
  double t = 0.0;
  double z_prev = z_at(0);
  for (int i = 0; i < 1000; ++i) {
    if (pace) std::this_thread::sleep_until(start + std::chrono::microseconds(1000 * i));
    const double z = z_at(i);
    const PoseSample pose = test::MakePose(i + 1, Vector3(0, 0, z));
    const WrenchOutput& out = renderer->Tick(t, &pose);
    t += renderer->dt();
    // The force of this tick acts while the hand moves to the next pose.
    cycle.work += out.wrench.f_W.z() * (z_at(i + 1) - z);
    cycle.peak_force = std::max(cycle.peak_force, out.wrench.f_W.norm());
    cycle.flags_seen |= out.flags;
    z_prev = z;
  }
  (void)z_prev;
  cycle.ticks = 1000;
  return cycle;
}

TEST(GeometryThread, NoEnergyGainOverPressHoldReleaseWithGeometryAt50Hz) {
  SceneConfig config = ThreadedBoxOnBox();
  config.contact.damping = 0.0;  // nothing to hide an energy gain behind but the coupling's damper
  const SceneModels models = BuildSceneModels(config);

  // Reference: geometry in the tick.
  SceneConfig sync_config = config;
  sync_config.contact.geometry_thread = GeometryThreadMode::kOff;
  HapticRenderer sync(sync_config, models);
  const PressCycle reference = RunPressCycle(&sync, /*pace=*/false);

  HapticRenderer renderer(config, models);
  GeometryThreadOptions slow;
  slow.min_query_time_s = 0.020;  // 50 Hz, each answer 20 ms late
  GeometryThread thread(&renderer.geometry_worker(), slow);
  renderer.set_geometry_worker_running(true);
  thread.Start();
  const PressCycle cycle = RunPressCycle(&renderer, /*pace=*/true);
  thread.Stop();
  renderer.set_geometry_worker_running(false);

  ASSERT_GT(reference.peak_force, 3.0);
  ASSERT_GT(cycle.peak_force, 3.0);
  EXPECT_GT(renderer.counts().geometry_async_ticks, 900);
  EXPECT_LE(renderer.counts().model_updates, 70);
  // The energy stored at the deepest point, for scale: k_series d^2 / 2.
  const double stored = 0.5 * 750.0 * 0.006 * 0.006;
  std::printf("work on the hand over the cycle: synchronous %.3g J, geometry at 50 Hz %.3g J (stored %.3g J)\n",
              reference.work, cycle.work, stored);
  EXPECT_LE(reference.work, 0.01 * stored);
  EXPECT_LE(cycle.work, 0.01 * stored);
}

// The worker's last answer can be left untaken when the queries go back into
// the tick (auto mode's switch, or the loop stopping its thread). When they
// leave it again, that answer is for a pose hundreds of ticks old: it must
// be dropped (counted), never rendered as the newest contact, which aged the
// model past its limit at once (e2e box_on_box: a model 5641 ticks old).
TEST(GeometryWorker, AnAnswerLeftUntakenIsNotRenderedWhenTheQueriesLeaveTheTickAgain) {
  AsyncBoxOnBox box;
  HapticRenderer& renderer = box.renderer;
  ASSERT_TRUE(renderer.geometry_async());
  double t = 0.0;
  int64_t seq = 0;
  int32_t flags = 0;
  auto tick_at = [&](double z) {
    const PoseSample pose = test::MakePose(++seq, Vector3(0, 0, z));
    flags |= renderer.Tick(t, &pose).flags;
    t += renderer.dt();
  };
  tick_at(0.007);                          // posts a pose 3 mm into the table
  renderer.geometry_worker().RunOnce();    // answered; nobody takes it
  renderer.set_geometry_worker_running(false);
  ASSERT_FALSE(renderer.geometry_async());
  for (int i = 0; i < 300; ++i) tick_at(0.03);  // in the tick, 2 cm above the table
  ASSERT_EQ(renderer.model_age_ticks(), 0);
  renderer.set_geometry_worker_running(true);
  ASSERT_TRUE(renderer.geometry_async());
  tick_at(0.03);  // takes the answer left untaken 301 ticks ago
  EXPECT_EQ(renderer.counts().model_outdated_answers, 1);
  EXPECT_EQ(renderer.model_age_ticks(), 1);  // still the last in-tick answer
  EXPECT_EQ(flags & kFlagModelStale, 0);
  EXPECT_EQ(renderer.counts().model_stale_ticks, 0);
  renderer.geometry_worker().RunOnce();
  tick_at(0.03);
  EXPECT_EQ(renderer.model_age_ticks(), 1);  // the worker's fresh answer is taken
  EXPECT_EQ(renderer.counts().model_outdated_answers, 1);
  renderer.set_geometry_worker_running(false);
}

TEST(GeometryThread, ModelAgesOutWhenTheGeometryThreadStops) {
  SceneConfig config = ThreadedBoxOnBox();
  config.contact.model_max_age_s = 0.1;
  config.contact.model_age_ramp_s = 0.05;
  const SceneModels models = BuildSceneModels(config);
  HapticRenderer renderer(config, models);
  GeometryThread thread(&renderer.geometry_worker(), {});
  renderer.set_geometry_worker_running(true);
  thread.Start();
  double t = 0.0;
  int64_t seq = 0;
  const auto start = Clock::now();
  int tick = 0;
  auto run = [&](int n, int32_t* flags_seen) {
    for (int i = 0; i < n; ++i, ++tick) {
      std::this_thread::sleep_until(start + std::chrono::microseconds(1000 * tick));
      const PoseSample pose = test::MakePose(++seq, Vector3(0, 0, 0.007));  // 3 mm into the table
      *flags_seen |= renderer.Tick(t, &pose).flags;
      t += renderer.dt();
    }
  };
  int32_t flags = 0;
  run(300, &flags);
  ASSERT_GT(renderer.contact().wrench.w0.f_W.z(), 1.0);
  EXPECT_EQ(flags & kFlagModelStale, 0);
  EXPECT_LT(renderer.model_age_ticks(), 50);
  thread.Stop();  // the geometry stalls; the renderer still expects answers
  flags = 0;
  run(90, &flags);
  EXPECT_GT(renderer.contact().wrench.w0.f_W.z(), 1.0);  // within model_max_age_ms: still pushing
  run(80, &flags);
  EXPECT_GE(renderer.model_age_ticks(), 160);
  EXPECT_EQ(renderer.contact().wrench.w0.f_W.norm(), 0.0);
  EXPECT_EQ(renderer.contact().wrench.K.norm(), 0.0);
  EXPECT_TRUE(flags & kFlagModelStale);
  EXPECT_GT(renderer.counts().model_stale_ticks, 0);
  renderer.set_geometry_worker_running(false);
}

}  // namespace
}  // namespace haptics
