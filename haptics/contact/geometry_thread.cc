#include "haptics/contact/geometry_thread.h"

#include <spdlog/spdlog.h>
#include <time.h>

#include <cerrno>
#include <chrono>
#include <string>

#include "haptics/loop/monotonic_clock.h"
#include "haptics/loop/realtime.h"

namespace haptics {

GeometryWorker::GeometryWorker(ContactGeometry* geometry) : geometry_(geometry) {
  const int n = geometry_->num_objects();
  answers_.ForEachSlot([n](ContactSnapshot& s) { s.Reserve(n); });
}

void GeometryWorker::Post(const Isometry3& X_WT, int64_t tick) {
  GeometryRequest& r = requests_.WriteSlot();
  r.X_WT = X_WT;
  r.tick = tick;
  posted_.store(tick);
  requests_.Publish();
}

bool GeometryWorker::idle() const { return !busy_.load() && answered_.load() == posted_.load(); }

bool GeometryWorker::RunOnce(double min_query_time_s) {
  const int64_t start = MonotonicNowNs();
  busy_.store(true);
  const GeometryRequest* request = requests_.TakeNewest();
  if (request == nullptr) {
    busy_.store(false);
    return false;
  }
  ContactSnapshot& answer = answers_.WriteSlot();
  geometry_->Query(request->X_WT, request->tick, &answer);
  const int64_t tick = request->tick;
  if (min_query_time_s > 0.0) SleepUntilNs(start + static_cast<int64_t>(min_query_time_s * 1e9));
  last_query_us_.store(answer.query_us, std::memory_order_relaxed);
  queries_.fetch_add(1, std::memory_order_relaxed);
  answers_.Publish();
  answered_.store(tick);
  // Then, until the servo posts its next pose, the work the query left for
  // after its answer (candidate-list rebuilds): off the answer's path.
  geometry_->PrepareNext(
      [this, tick] { return posted_.load(std::memory_order_relaxed) != tick; });
  busy_.store(false);
  return true;
}

GeometryThread::GeometryThread(GeometryWorker* worker, const GeometryThreadOptions& options)
    : worker_(worker), options_(options) {}

GeometryThread::~GeometryThread() { Stop(); }

void GeometryThread::Start() {
  stop_ = false;
  finished_ = false;
  thread_ = std::thread([this] { Run(); });
}

void GeometryThread::Stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

bool GeometryThread::WaitFinished(double timeout_s) const {
  const int64_t until = MonotonicNowNs() + static_cast<int64_t>(timeout_s * 1e9);
  while (!finished_.load()) {
    if (MonotonicNowNs() >= until) return false;
    SleepUntilNs(MonotonicNowNs() + 1'000'000);
  }
  return true;
}

void GeometryThread::Run() {
  NameThisThread("geometry");
  PrefaultThread();
  std::string why;
  // The server's threads inherit SCHED_FIFO from main; a query of hundreds
  // of milliseconds at a real-time priority would starve the rest of its CPU.
  if (options_.realtime_priority > 0) {
    if (!TrySetFifoScheduling(options_.realtime_priority, &why))
      spdlog::warn("geometry thread: no real-time scheduling ({})", why);
  } else if (!TrySetNormalScheduling(&why)) {
    spdlog::warn("geometry thread: {}", why);
  }
  if (options_.cpu >= 0) {
    pinned_ = TryPinToCpu(options_.cpu, &why);
    if (pinned_) {
      spdlog::info("geometry thread: pinned to CPU {}", options_.cpu);
    } else {
      spdlog::warn("geometry thread: not pinned ({})", why);
    }
  }
  const int64_t idle_ns = static_cast<int64_t>(options_.idle_sleep_us * 1e3);
  while (!stop_.load(std::memory_order_relaxed)) {
    const int64_t start = MonotonicNowNs();
    if (!worker_->RunOnce(options_.min_query_time_s)) SleepUntilNs(start + idle_ns);
  }
  finished_ = true;
}

}  // namespace haptics
