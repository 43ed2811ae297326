#pragma once
// Clocks shared by the probes. Message utimes are CLOCK_MONOTONIC microseconds
// (see msgs/probe_pose_t.lcm); LCM log event timestamps are wall-clock
// microseconds since the UNIX epoch (LCM's own convention).
#include <cstdint>
#include <ctime>

namespace probes {

inline int64_t MonotonicNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}

inline int64_t MonotonicUs() { return MonotonicNs() / 1000; }

inline int64_t WallClockUs() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return int64_t{ts.tv_sec} * 1'000'000 + ts.tv_nsec / 1000;
}

// Sleeps until an absolute CLOCK_MONOTONIC time. Absolute deadlines keep a
// periodic loop from drifting: a late wake-up does not delay later samples.
inline void SleepUntilNs(int64_t deadline_ns) {
  timespec ts{};
  ts.tv_sec = deadline_ns / 1'000'000'000;
  ts.tv_nsec = deadline_ns % 1'000'000'000;
  // EINTR (a signal) only shortens the sleep; retry until the deadline.
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) != 0) {
  }
}

}  // namespace probes
