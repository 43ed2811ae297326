#pragma once
// CLOCK_MONOTONIC in nanoseconds and absolute sleeps on it, for the servo
// loop and the geometry thread (the same clock LCM receipt times use).
#include <time.h>

#include <cerrno>
#include <cstdint>

namespace haptics {

inline int64_t MonotonicNowNs() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

// CPU time this thread has run, in nanoseconds (CLOCK_THREAD_CPUTIME_ID: a
// system call, ~0.5 us here; time the thread was not running, preempted or
// its vCPU descheduled by the hypervisor, is not counted).
inline int64_t ThreadCpuNowNs() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

// Sleeps until the absolute time t_ns (TIMER_ABSTIME: no drift), through signals.
inline void SleepUntilNs(int64_t t_ns) {
  timespec ts;
  ts.tv_sec = t_ns / 1'000'000'000;
  ts.tv_nsec = t_ns % 1'000'000'000;
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

}  // namespace haptics
