#pragma once
// The geometry thread: PD queries for all pairs in reach on a thread of their
// own, so that the servo tick never waits for them (issue: a cold PolyDepth
// query on real meshes takes milliseconds to tens of milliseconds).
//
// GeometryWorker is the hand-over, free of threads: the servo tick posts the
// tool pose (Post) and takes the newest answer if there is one (TakeAnswer);
// RunOnce, on the geometry side, queries ContactGeometry at the newest posted
// pose (older ones are skipped: always the newest pose, warm-started from the
// geometry's own previous answer) and publishes the answer. Both directions
// go through LatestValue (lock-free triple buffers): neither side ever waits
// for the other, and the answer slots are sized once, so nothing allocates.
// GeometryThread runs RunOnce in a loop on its own (pinned) thread, sleeping
// briefly when there is no new pose. Tests drive RunOnce by hand.
#include <atomic>
#include <cstdint>
#include <thread>

#include "haptics/contact/contact_geometry.h"
#include "haptics/loop/latest_value.h"
#include "haptics/tool/spatial.h"

namespace haptics {

struct GeometryRequest {
  Isometry3 X_WT = Isometry3::Identity();  // tool pose to query at
  int64_t tick = -1;                       // servo tick that posted it
};

class GeometryWorker {
 public:
  // `geometry` must outlive the worker; while the worker is not idle() only
  // RunOnce touches it.
  explicit GeometryWorker(ContactGeometry* geometry);
  GeometryWorker(const GeometryWorker&) = delete;
  GeometryWorker& operator=(const GeometryWorker&) = delete;

  // Servo side.
  void Post(const Isometry3& X_WT, int64_t tick);
  const ContactSnapshot* TakeAnswer() { return answers_.TakeNewest(); }
  // Every posted pose has been answered and no query runs: the caller may
  // use the geometry itself until it posts again.
  bool idle() const;
  int64_t posted_tick() const { return posted_.load(); }

  // Geometry side: one query at the newest posted pose, if a new one was
  // posted. Returns whether it queried. min_query_time_s > 0 holds the
  // answer back until that long after the query started (a slow geometry
  // on purpose, for tests).
  bool RunOnce(double min_query_time_s = 0.0);

  // Totals, readable from any thread.
  int64_t queries() const { return queries_.load(std::memory_order_relaxed); }
  double last_query_us() const { return last_query_us_.load(std::memory_order_relaxed); }

 private:
  ContactGeometry* geometry_;
  LatestValue<GeometryRequest> requests_;
  LatestValue<ContactSnapshot> answers_;
  std::atomic<bool> busy_{false};
  std::atomic<int64_t> posted_{-1}, answered_{-1};
  std::atomic<int64_t> queries_{0};
  std::atomic<double> last_query_us_{0.0};
};

struct GeometryThreadOptions {
  int cpu = -1;                // pin to this CPU (-1: no pinning)
  int realtime_priority = 0;   // SCHED_FIFO priority (0: stay SCHED_OTHER)
  double idle_sleep_us = 100;  // nap when no new pose was posted
  // Each query takes at least this long (s): slows the thread down on
  // purpose, for tests of the servo side (0: off).
  double min_query_time_s = 0.0;
};

class GeometryThread {
 public:
  GeometryThread(GeometryWorker* worker, const GeometryThreadOptions& options);
  ~GeometryThread();
  GeometryThread(const GeometryThread&) = delete;
  GeometryThread& operator=(const GeometryThread&) = delete;

  void Start();
  void Stop();  // after the current query; idempotent
  // Asks the thread to stop after its current query without waiting for it
  // (a PolyDepth query can take long); Stop() or the destructor joins.
  void RequestStop() { stop_ = true; }
  // After RequestStop: waits up to timeout_s for the thread to finish its
  // query; true if it has (then Stop() joins at once).
  bool WaitFinished(double timeout_s) const;
  bool pinned() const { return pinned_; }

 private:
  void Run();
  GeometryWorker* worker_;
  GeometryThreadOptions options_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> finished_{true};
  bool pinned_ = false;
};

}  // namespace haptics
