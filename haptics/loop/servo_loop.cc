#include "haptics/loop/servo_loop.h"

#include <spdlog/spdlog.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <string>

#include "haptics/loop/monotonic_clock.h"
#include "haptics/loop/realtime.h"

namespace haptics {
namespace {

size_t WindowTicks(const ServoLoopOptions& o) {
  return static_cast<size_t>(std::max(1.0, std::round(o.rate_hz / o.status_rate_hz)));
}

// Pose-triggered ticks lock the pose's arrival to the middle of the window.
PhaseLockOptions PhaseLockFor(const ServoLoopOptions& o) {
  PhaseLockOptions p = o.phase_lock;
  if (o.trigger == TickTrigger::kPose && o.arrivals != nullptr)
    p.target_us = std::min(0.5 * o.pose_window_us, 0.25e6 / o.rate_hz);
  return p;
}

}  // namespace

ServoLoop::ServoLoop(HapticRenderer* renderer, LatestValue<PoseSample>* poses, WrenchSink* sink,
                     const ServoLoopOptions& options)
    : renderer_(renderer), poses_(poses), sink_(sink), options_(options),
      window_jitter_us_(WindowTicks(options)), window_compute_us_(WindowTicks(options)),
      window_wake_us_(WindowTicks(options)), window_age_(WindowTicks(options)),
      phase_lock_(PhaseLockFor(options), 1e6 / options.rate_hz),
      misses_by_cause_(std::llround(1e9 / options.rate_hz)) {}

ServoLoop::~ServoLoop() {
  Stop();
  if (geometry_thread_) {
    geometry_thread_->Stop();
    renderer_->set_geometry_worker_running(false);
  }
}

void ServoLoop::Start() {
  stop_ = false;
  if (renderer_->wants_geometry_thread()) {
    GeometryThreadOptions g = options_.geometry;
    if (g.cpu < 0 && options_.cpu >= 0 && NumCpus() >= 2) g.cpu = options_.cpu == 0 ? 1 : 0;
    if (g.cpu >= NumCpus()) g.cpu = -1;
    geometry_thread_ = std::make_unique<GeometryThread>(&renderer_->geometry_worker(), g);
    renderer_->set_geometry_worker_running(true);
    geometry_thread_->Start();
  }
  thread_ = std::thread([this] { Run(); });
}

void ServoLoop::Stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  // The geometry thread finishes its query in its own time (it may take
  // long); the destructor joins it. Summary() does not need it.
  if (geometry_thread_) geometry_thread_->RequestStop();
}

void ServoLoop::SetUpThread() {
  NameThisThread("servo_loop");
  PrefaultThread();
  std::string why;
  if (options_.realtime_priority > 0) {
    realtime_ = TrySetFifoScheduling(options_.realtime_priority, &why);
    if (realtime_) {
      spdlog::info("servo loop: SCHED_FIFO priority {}", options_.realtime_priority);
    } else {
      spdlog::warn("servo loop: no real-time scheduling ({}); running SCHED_OTHER, expect more jitter", why);
    }
  }
  if (options_.cpu >= 0) {
    pinned_ = TryPinToCpu(options_.cpu, &why);
    if (pinned_) {
      spdlog::info("servo loop: pinned to CPU {}", options_.cpu);
    } else {
      spdlog::warn("servo loop: not pinned ({}); the scheduler may migrate it", why);
    }
  }
}

void ServoLoop::Run() {
  SetUpThread();
  const int64_t period_ns = std::llround(1e9 / options_.rate_hz);
  const size_t window = WindowTicks(options_);
  start_ns_ = MonotonicNowNs();
  int64_t next = start_ns_ + period_ns;
  int64_t prev_wake = -1;
  double period_us = 0.0;
  int64_t window_start = start_ns_;
  int64_t window_ticks = 0;
  const bool by_pose_mode = options_.trigger == TickTrigger::kPose && options_.arrivals != nullptr;
  bool previous_took_pose = false;
  int64_t phase_offset_ns = 0;  // sum of the phase lock's shifts
  int64_t last_receipt_ns = 0, last_utime_us = 0;  // of the last pose taken
  int64_t previous_deadline = 0;
  int64_t cpu_before = ThreadCpuNowNs();  // the thread's CPU time at the previous tick's end
  const int64_t window_ns = std::clamp<int64_t>(std::llround(options_.pose_window_us * 1e3), 0, period_ns / 2);
  while (!stop_.load(std::memory_order_relaxed)) {
    bool by_pose = false;
    int64_t open = next;
    if (by_pose_mode) {
      // The window opens pose_window_us before the deadline; a pose arriving
      // in it starts the tick, else the deadline does. A pose that came
      // before the window opened does not start the tick: a fresher one is
      // due in the window (it would otherwise lock the loop into taking each
      // pose a period late), and the deadline renders it if none comes.
      open = next - window_ns;
      SleepUntilNs(open);
      const uint32_t seen = options_.arrivals->count();
      by_pose = options_.arrivals->WaitUntil(seen, next);
    } else {
      SleepUntilNs(next);
    }
    const int64_t wake = MonotonicNowNs();
    if (prev_wake >= 0) {
      period_us = static_cast<double>(wake - prev_wake) * 1e-3;
      const double jitter_us = std::abs(static_cast<double>(wake - prev_wake - period_ns)) * 1e-3;
      window_jitter_us_.Add(jitter_us);
      jitter_hist_.Add(jitter_us);
    }
    prev_wake = wake;
    const double t = static_cast<double>(next - start_ns_) * 1e-9;
    const PoseSample* pose = poses_->TakeNewest();
    by_pose = by_pose && pose != nullptr;
    ++(by_pose ? ticks_by_pose_ : ticks_by_deadline_);
    // When the tick should have started: at the window's opening, the pose's
    // arrival if later, the deadline at the latest (a pose that came while
    // the loop was not running does not excuse its late start).
    const int64_t scheduled = by_pose ? std::min(next, std::max(open, pose->receive_time_ns)) : next;
    const double wake_late_us = static_cast<double>(std::max<int64_t>(0, wake - scheduled)) * 1e-3;
    window_wake_us_.Add(wake_late_us);
    wake_hist_.Add(wake_late_us);
    if (wake_late_us >= options_.late_wakeup_us) ++late_wakeups_;
    const WrenchOutput& out = renderer_->Tick(t, pose);
    sink_->Publish(out);
    if (const int64_t age = renderer_->model_age_ticks(); age >= 0) {
      window_age_.Add(static_cast<double>(age));
      age_hist_.Add(static_cast<double>(age));
    }
    // Follow the device's clock: move the schedule toward a fixed wait after
    // the pose's receipt (the rate stays nominal; see phase_lock.h).
    int64_t phase_shift_ns = 0;
    if (pose != nullptr && pose->receive_time_ns > 0 && pose->receive_time_ns <= wake) {
      const double wait_us = static_cast<double>(wake - pose->receive_time_ns) * 1e-3;
      pose_wait_hist_.Add(wait_us);
      const int64_t previous_receipt = last_receipt_ns, previous_utime = last_utime_us;
      last_receipt_ns = pose->receive_time_ns;
      last_utime_us = pose->utime;
      if (by_pose_mode) {
        // Lock the deadline to the arrivals: the pose should come in the
        // middle of the window. Its lead on the deadline: beyond the window
        // it waited for the window to open (move earlier), except a pose
        // that just missed the previous deadline, which ticked without one:
        // that pose came late (move later).
        double lead_us = static_cast<double>(next - pose->receive_time_ns) * 1e-3;
        const double period_us = static_cast<double>(period_ns) * 1e-3;
        if (!previous_took_pose && pose->receive_time_ns > previous_deadline && lead_us > 0.5 * period_us)
          lead_us -= period_us;
        // Transport only ever delays: a pose that came much closer after the
        // previous one than the sender sent them follows a delayed one (a
        // burst); its earliness says nothing about the sender's phase, and
        // counting it would pull the deadlines earlier after every stall.
        const double receipt_gap_us = static_cast<double>(pose->receive_time_ns - previous_receipt) * 1e-3;
        const double send_gap_us = static_cast<double>(pose->utime - previous_utime);
        const bool after_burst = previous_receipt > 0 && send_gap_us > 0.0 && receipt_gap_us < send_gap_us - 0.25 * period_us;
        if (!after_burst) phase_shift_ns = std::llround(phase_lock_.Update(lead_us) * 1e3);
      } else {
        phase_shift_ns = std::llround(phase_lock_.Update(wait_us) * 1e3);
      }
    }

    const int64_t end = MonotonicNowNs();
    const double compute_us = static_cast<double>(end - wake) * 1e-3;
    window_compute_us_.Add(compute_us);
    compute_hist_.Add(compute_us);
    // The tick's CPU time: the thread's CPU time since the previous tick's
    // end (the sleep takes none), at most the tick's wall time. The cap
    // matters on this VM: a wake-up delayed by milliseconds can come with
    // as much CPU time charged to the thread before it ran its tick (time
    // stolen from the vCPU while the thread was current is not always
    // subtracted); that is the late wake-up's, not the tick's.
    const int64_t cpu_now = ThreadCpuNowNs();
    const int64_t cpu_ns = std::min(cpu_now - cpu_before, end - wake);
    cpu_before = cpu_now;
    cpu_hist_.Add(static_cast<double>(cpu_ns) * 1e-3);
    ++ticks_;
    // The phase follows the pose, never the rate: the deadlines stay within
    // a period of the nominal grid (any phase is reachable), so over a run
    // the tick count is the nominal rate times the time, within one tick,
    // whatever the sender's clock does.
    phase_shift_ns = std::clamp(phase_shift_ns, -period_ns - phase_offset_ns, period_ns - phase_offset_ns);
    phase_offset_ns += phase_shift_ns;
    previous_took_pose = pose != nullptr;
    previous_deadline = next;
    next += period_ns + phase_shift_ns;  // this tick's deadline: the next tick's start
    const bool missed = end > next;
    switch (misses_by_cause_.Classify({scheduled, wake, end, next, cpu_ns}, renderer_->tick_work())) {
      case MissCause::kNone: break;
      case MissCause::kLateWakeup: ++misses_late_; break;
      case MissCause::kStalled: ++misses_stalled_; break;
      case MissCause::kCharged: ++misses_charged_; break;
      case MissCause::kCompute: ++misses_compute_; break;
    }
    if (missed) {
      ++misses_;
      // More than a whole period late: skip the lost slots, do not burst.
      if (end > next + period_ns) next += ((end - next) / period_ns) * period_ns;
    }
    if (options_.tick_log != nullptr) {
      options_.tick_log->Add({static_cast<float>(period_us), static_cast<float>(compute_us),
                              out.contact_count, out.flags, missed});
    }
    if (++window_ticks >= static_cast<int64_t>(window)) {
      PublishStatus(end, window_ticks, end - window_start);
      window_start = end;
      window_ticks = 0;
    }
  }
  end_ns_ = MonotonicNowNs();
}

void ServoLoop::PublishStatus(int64_t now_ns, int64_t window_ticks, int64_t window_ns) {
  LoopStatus& s = status_.WriteSlot();
  s.time_ns = now_ns;
  s.tick_count = ticks_;
  s.target_rate_hz = options_.rate_hz;
  s.achieved_rate_hz = window_ns > 0 ? 1e9 * static_cast<double>(window_ticks) / window_ns : 0.0;
  s.jitter_us = window_jitter_us_.Summarize();
  s.compute_us = window_compute_us_.Summarize();
  s.deadline_misses = misses_;
  s.misses_compute = misses_compute_;
  s.misses_stalled = misses_stalled_;
  s.misses_charged = misses_charged_;
  s.misses_late_wakeup = misses_late_;
  s.late_wakeups = late_wakeups_;
  s.wake_latency_us = window_wake_us_.Summarize();
  s.model_age_ticks = window_age_.Summarize();
  s.realtime = realtime_;
  s.renderer = renderer_->counts();
  s.geometry_async = renderer_->geometry_async();
  s.pd_update_rate_hz = window_ns > 0 ? 1e9 * static_cast<double>(s.renderer.model_updates - window_updates_start_) /
                                            static_cast<double>(window_ns)
                                      : 0.0;
  window_updates_start_ = s.renderer.model_updates;
  status_.Publish();
  window_jitter_us_.Clear();
  window_compute_us_.Clear();
  window_wake_us_.Clear();
  window_age_.Clear();
}

LoopSummary ServoLoop::Summary() const {
  LoopSummary s;
  s.ticks = ticks_;
  s.elapsed_s = end_ns_ > start_ns_ ? 1e-9 * static_cast<double>(end_ns_ - start_ns_) : 0.0;
  s.achieved_rate_hz = s.elapsed_s > 0.0 ? ticks_ / s.elapsed_s : 0.0;
  s.deadline_misses = misses_;
  s.misses_compute = misses_compute_;
  s.misses_stalled = misses_stalled_;
  s.misses_charged = misses_charged_;
  s.misses_late_wakeup = misses_late_;
  s.late_wakeups = late_wakeups_;
  s.wake_latency_p50_us = wake_hist_.Percentile(0.50);
  s.wake_latency_p99_us = wake_hist_.Percentile(0.99);
  s.wake_latency_max_us = wake_hist_.max();
  s.model_age_p50_ticks = age_hist_.PercentileFloor(0.50);
  s.model_age_p99_ticks = age_hist_.PercentileFloor(0.99);
  s.model_age_max_ticks = age_hist_.max();
  s.geometry_thread = geometry_thread_ != nullptr;
  s.pose_triggered = options_.trigger == TickTrigger::kPose && options_.arrivals != nullptr;
  s.ticks_by_pose = ticks_by_pose_;
  s.ticks_by_deadline = ticks_by_deadline_;
  s.jitter_p99_us = jitter_hist_.Percentile(0.99);
  s.jitter_max_us = jitter_hist_.max();
  s.compute_p50_us = compute_hist_.Percentile(0.50);
  s.compute_p99_us = compute_hist_.Percentile(0.99);
  s.compute_max_us = compute_hist_.max();
  s.tick_cpu_p99_us = cpu_hist_.Percentile(0.99);
  s.tick_cpu_max_us = cpu_hist_.max();
  s.poses_taken = pose_wait_hist_.count();
  s.pose_wait_p50_us = pose_wait_hist_.Percentile(0.50);
  s.pose_wait_p99_us = pose_wait_hist_.Percentile(0.99);
  s.realtime = realtime_;
  s.pinned = pinned_;
  s.renderer = renderer_->counts();
  s.pd_update_rate_hz = s.elapsed_s > 0.0 ? s.renderer.model_updates / s.elapsed_s : 0.0;
  return s;
}

}  // namespace haptics
