#pragma once
// The fixed-rate servo thread. Each tick: take the newest pose (lock-free,
// latest_value.h), run the renderer, hand the wrench to the sink. Ticks run
// on absolute deadlines (clock_nanosleep TIMER_ABSTIME, CLOCK_MONOTONIC), so
// the rate does not drift with compute time. The thread asks for SCHED_FIFO
// and a CPU of its own and logs a fallback if refused.
//
// Measured per tick, into preallocated buffers: period jitter |actual period
// - nominal|, compute time (wake-up to after the sink returns), the thread's
// CPU time over the tick (one CLOCK_THREAD_CPUTIME_ID read after the send),
// deadline misses (a tick finishing after the next tick's start; a tick more than a
// period late skips the missed slots instead of bursting). At status_rate_hz
// the loop summarises its window (nth_element on a preallocated copy) into a
// LoopStatus the main thread takes without locks. With
// ServoLoopOptions::tick_log set, every tick also appends a TickRecord to
// that preallocated log (timing_stats.h).
#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>

#include "haptics/loop/arrival_signal.h"
#include "haptics/contact/geometry_thread.h"
#include "haptics/haptic_renderer.h"
#include "haptics/loop/latest_value.h"
#include "haptics/loop/miss_cause.h"
#include "haptics/loop/phase_lock.h"
#include "haptics/io/pose_sample.h"
#include "haptics/loop/timing_stats.h"
#include "haptics/io/wrench_output.h"

namespace haptics {

// Where each tick's wrench goes (LCM in the server). Called on the loop
// thread: must not block or allocate.
class WrenchSink {
 public:
  virtual ~WrenchSink() = default;
  virtual void Publish(const WrenchOutput& output) = 0;
};

// What starts a tick.
enum class TickTrigger {
  // Default: the tick that renders a pose starts when the pose arrives (its
  // arrival wakes the loop through an ArrivalSignal), at most once per period:
  // a pose arriving up to pose_window_us before the tick's deadline starts
  // it; the deadline starts it when no pose comes. The deadlines keep the
  // fixed rate; the phase lock moves them (<= max_step_us per tick) so that
  // poses arrive mid-window: the tick's phase follows the pose, the rate stays
  // nominal for a missing or bursty sender.
  kPose,
  // Fixed-rate deadlines only (the phase lock still moves them so that the
  // newest pose waits about phase_lock.target_us).
  kFixedRate,
};

struct ServoLoopOptions {
  double rate_hz = 1000.0;
  int cpu = -1;                 // -1: no pinning
  int realtime_priority = 80;   // 0: do not ask for SCHED_FIFO
  double status_rate_hz = 10.0;
  TickLog* tick_log = nullptr;  // optional: one TickRecord per tick (not owned)
  PhaseLockOptions phase_lock;  // tick phase follows pose arrival (phase_lock.h)
  TickTrigger trigger = TickTrigger::kPose;
  ArrivalSignal* arrivals = nullptr;  // kPose needs it (not owned); without it: fixed rate
  double pose_window_us = 400.0;      // kPose: how early before the deadline a pose may start its tick
  // The geometry thread, started with the loop when the renderer wants one
  // (contact.geometry_thread on/auto). cpu -1: the other CPU than `cpu` when
  // there are two or more, else unpinned.
  GeometryThreadOptions geometry;
  // A wake-up this late (us) or later counts as a late wake-up (the same
  // threshold as the cyclictest floor the loop benchmark counts).
  double late_wakeup_us = 1000.0;
};

// One status window (about 1 / status_rate_hz of ticks). Times in us.
struct LoopStatus {
  int64_t time_ns = 0;           // CLOCK_MONOTONIC at the end of the window
  int64_t tick_count = 0;        // total
  double target_rate_hz = 0.0;
  double achieved_rate_hz = 0.0;  // this window
  TimingSummary jitter_us;        // this window
  TimingSummary compute_us;       // this window
  int64_t deadline_misses = 0;    // total
  // Of those, by cause (each miss has one; miss_cause.h):
  //  compute: the tick's own CPU time overran its period and no tick of as
  //    much counted work ran in half a period (ours to fix);
  //  charged: its CPU time overran, but ticks of as much work ran in half a
  //    period: time the platform charged to the thread (interrupts, VM exits);
  //  stalled: its CPU time fit, but the thread was not running for long
  //    enough inside the tick to miss (preempted by another thread or an
  //    interrupt, or its vCPU descheduled by the hypervisor: the platform's);
  //  late wake-up: it woke up so late that its tick did not fit (the platform's).
  int64_t misses_compute = 0;     // total
  int64_t misses_charged = 0;     // total
  int64_t misses_stalled = 0;     // total
  int64_t misses_late_wakeup = 0; // total
  int64_t late_wakeups = 0;       // total wake-ups >= late_wakeup_us late
  TimingSummary wake_latency_us;  // this window: wake-up - scheduled start
  TimingSummary model_age_ticks;  // this window: age of the contact model rendered
  double pd_update_rate_hz = 0.0; // this window: geometry answers taken per second
  bool geometry_async = false;    // the tick renders the geometry thread's answers
  bool realtime = false;          // SCHED_FIFO granted
  RendererCounts renderer;        // totals
};

// The whole run, after Stop().
struct LoopSummary {
  int64_t ticks = 0;
  double elapsed_s = 0.0;
  double achieved_rate_hz = 0.0;
  int64_t deadline_misses = 0;
  int64_t misses_compute = 0, misses_charged = 0, misses_stalled = 0, misses_late_wakeup = 0;  // see LoopStatus
  int64_t late_wakeups = 0;
  double wake_latency_p50_us = 0.0, wake_latency_p99_us = 0.0, wake_latency_max_us = 0.0;
  double model_age_p50_ticks = 0.0, model_age_p99_ticks = 0.0, model_age_max_ticks = 0.0;
  double pd_update_rate_hz = 0.0;  // geometry answers taken per second
  bool geometry_thread = false;    // a geometry thread ran
  double jitter_p99_us = 0.0, jitter_max_us = 0.0;
  double compute_p50_us = 0.0, compute_p99_us = 0.0, compute_max_us = 0.0;
  // The thread's CPU time per tick (compute minus the time it did not run).
  double tick_cpu_p99_us = 0.0, tick_cpu_max_us = 0.0;
  bool realtime = false;
  bool pinned = false;
  // Receipt-to-tick wait of the poses the ticks took (us): the part of the
  // pose-to-wrench latency the loop adds (phase_lock.h keeps it near its target).
  int64_t poses_taken = 0;
  double pose_wait_p50_us = 0.0, pose_wait_p99_us = 0.0;
  bool pose_triggered = false;     // TickTrigger::kPose was in effect
  int64_t ticks_by_pose = 0;       // ticks a pose arrival started
  int64_t ticks_by_deadline = 0;   // ticks the deadline started
  RendererCounts renderer;
};

class ServoLoop {
 public:
  // All pointees must outlive the loop.
  ServoLoop(HapticRenderer* renderer, LatestValue<PoseSample>* poses, WrenchSink* sink,
            const ServoLoopOptions& options);
  ~ServoLoop();
  ServoLoop(const ServoLoop&) = delete;
  ServoLoop& operator=(const ServoLoop&) = delete;

  void Start();
  // Stops after the current tick and joins. Idempotent. The geometry thread
  // is asked to stop; the destructor joins it.
  void Stop();
  // After Stop: waits up to timeout_s for the geometry thread to finish its
  // query (true at once without one).
  bool WaitGeometryFinished(double timeout_s) const {
    return !geometry_thread_ || geometry_thread_->WaitFinished(timeout_s);
  }

  // Reader side for the main thread (single reader).
  LatestValue<LoopStatus>& status() { return status_; }
  // Valid after Stop().
  LoopSummary Summary() const;

 private:
  void Run();
  void SetUpThread();
  void PublishStatus(int64_t now_ns, int64_t window_ticks, int64_t window_ns);

  HapticRenderer* renderer_;
  LatestValue<PoseSample>* poses_;
  WrenchSink* sink_;
  ServoLoopOptions options_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  LatestValue<LoopStatus> status_;

  // Loop-thread state (read by others only after join).
  SampleWindow window_jitter_us_, window_compute_us_, window_wake_us_, window_age_;
  DurationHistogram jitter_hist_, compute_hist_, cpu_hist_, pose_wait_hist_, wake_hist_, age_hist_;
  std::unique_ptr<GeometryThread> geometry_thread_;
  int64_t misses_compute_ = 0, misses_charged_ = 0, misses_stalled_ = 0, misses_late_ = 0, late_wakeups_ = 0;
  int64_t window_updates_start_ = 0;
  int64_t ticks_by_pose_ = 0, ticks_by_deadline_ = 0;
  PhaseLock phase_lock_;
  MissClassifier misses_by_cause_;
  int64_t ticks_ = 0;
  int64_t misses_ = 0;
  int64_t start_ns_ = 0, end_ns_ = 0;
  bool realtime_ = false, pinned_ = false;
};

}  // namespace haptics
