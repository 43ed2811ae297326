// cpu_stall_probe: the platform's floor for CPU time a running thread is
// charged without doing its work. The loop benchmark runs it beside each
// server run (as cyclictest measures the floor for late wake-ups).
//
// A thread pinned to --cpu at SCHED_FIFO --priority wakes every millisecond
// and runs a fixed chunk of arithmetic (calibrated to --chunk-us of CPU on an
// idle start). A chunk whose thread CPU time (CLOCK_THREAD_CPUTIME_ID) reaches
// --threshold-us did not take that long to compute: the time is what the
// platform charged to the running thread (interrupt and softirq work in its
// context, a vCPU descheduled by the hypervisor while the thread was on it).
// The servo loop counts a miss as compute-caused from the same clock, so this
// is the rate at which the platform alone would make it see one.
//
// Prints one key=value line: chunks, chunk_us (calibrated), cpu_stalls
// (chunks charged >= threshold), wall_stalls (chunks taking >= threshold of
// wall time: preempted as well), max_cpu_us, max_wall_us, realtime, pinned.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <string>

#include "haptics/loop/monotonic_clock.h"
#include "haptics/loop/realtime.h"

namespace {

volatile double g_sink;

// A fixed amount of work: the same instructions whatever the platform does.
void Work(int64_t n) {
  double x = 1.0;
  for (int64_t i = 0; i < n; ++i) x = x * 1.0000001 + 1e-9;
  g_sink = x;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Counts work chunks charged far more CPU time than their work takes"};
  int cpu = 1, priority = 78;
  double seconds = 30.0, chunk_us = 20.0, threshold_us = 1000.0;
  app.add_option("--cpu", cpu, "CPU to pin to (-1: none)");
  app.add_option("--priority", priority, "SCHED_FIFO priority (0: do not ask)")->check(CLI::Range(0, 99));
  app.add_option("--seconds", seconds, "how long to run")->check(CLI::PositiveNumber);
  app.add_option("--chunk-us", chunk_us, "CPU time of one chunk on an idle start")->check(CLI::Range(1.0, 500.0));
  app.add_option("--threshold-us", threshold_us, "a chunk charged this much CPU or more is a stall")
      ->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);

  bool pinned = false, realtime = false;
  std::string why;
  if (cpu >= 0 && !(pinned = haptics::TryPinToCpu(cpu, &why)))
    std::fprintf(stderr, "cpu_stall_probe: --cpu %d: %s\n", cpu, why.c_str());
  if (priority > 0 && !(realtime = haptics::TrySetFifoScheduling(priority, &why)))
    std::fprintf(stderr, "cpu_stall_probe: SCHED_FIFO %d: %s\n", priority, why.c_str());

  // Calibrate: the least of a few timings of a trial size, scaled.
  const int64_t trial = 100000;
  int64_t best_ns = INT64_MAX;
  for (int k = 0; k < 20; ++k) {
    const int64_t t0 = haptics::ThreadCpuNowNs();
    Work(trial);
    best_ns = std::min(best_ns, haptics::ThreadCpuNowNs() - t0);
  }
  const int64_t n = std::max<int64_t>(1, static_cast<int64_t>(trial * chunk_us * 1e3 / std::max<int64_t>(best_ns, 1)));

  const int64_t threshold_ns = static_cast<int64_t>(threshold_us * 1e3);
  int64_t chunks = 0, cpu_stalls = 0, wall_stalls = 0, max_cpu = 0, max_wall = 0, sum_cpu = 0;
  const int64_t end = haptics::MonotonicNowNs() + static_cast<int64_t>(seconds * 1e9);
  int64_t next = haptics::MonotonicNowNs();
  while (next < end) {
    next += 1'000'000;
    haptics::SleepUntilNs(next);
    const int64_t w0 = haptics::MonotonicNowNs(), c0 = haptics::ThreadCpuNowNs();
    Work(n);
    const int64_t c = haptics::ThreadCpuNowNs() - c0, w = haptics::MonotonicNowNs() - w0;
    ++chunks;
    sum_cpu += c;
    cpu_stalls += c >= threshold_ns;
    wall_stalls += w >= threshold_ns;
    max_cpu = std::max(max_cpu, c);
    max_wall = std::max(max_wall, w);
    // A late wake-up past several periods: do not burst to catch up.
    const int64_t now = haptics::MonotonicNowNs();
    if (now > next + 1'000'000) next += ((now - next) / 1'000'000) * 1'000'000;
  }
  std::printf(
      "cpu_stall_probe: chunks=%lld chunk_us=%.1f cpu_stalls=%lld wall_stalls=%lld max_cpu_us=%.1f "
      "max_wall_us=%.1f threshold_us=%.0f realtime=%d pinned=%d\n",
      static_cast<long long>(chunks), chunks > 0 ? 1e-3 * static_cast<double>(sum_cpu) / chunks : 0.0,
      static_cast<long long>(cpu_stalls), static_cast<long long>(wall_stalls), 1e-3 * max_cpu,
      1e-3 * max_wall, threshold_us, realtime ? 1 : 0, pinned ? 1 : 0);
  return 0;
}
