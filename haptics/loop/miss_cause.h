#pragma once
// Why a servo tick missed its deadline (it finished after the next tick's
// start). Each miss gets one cause:
//  - late wake-up: it started so late that it could not have fit had it
//    computed in no time beyond what it did (the platform's: the SCHED_FIFO
//    thread did not get the CPU when its start came);
//  - stalled: its CPU time fit the period, but the thread was not running
//    for long enough inside the tick (preempted, or its vCPU descheduled:
//    the platform's);
//  - charged: its CPU time overran the period, but a tick of at least as
//    much work ran in under half a period of CPU time earlier in the run, so
//    its work does not explain the overrun. Where the kernel does not account
//    interrupt time apart (no IRQ_TIME_ACCOUNTING) or the hypervisor spends a
//    VM exit on the vCPU, that time is charged to whatever thread runs: the
//    platform's. The loop benchmark's cpu_stall_probe measures that floor.
//  - compute: its CPU time overran and no tick of as much work ran in half a
//    period: ours to fix.
// Work is compared only for ticks whose work is counted (work >= 0): ticks
// that render the geometry thread's contact model, whose cost is a fixed
// amount per model term (HapticRenderer::tick_work). A tick that ran its
// geometry in line (work < 0) counts every CPU overrun as compute.
// Value type, no allocation: lives on the servo thread.
#include <cstdint>

namespace haptics {

enum class MissCause { kNone, kLateWakeup, kStalled, kCharged, kCompute };

// One tick's times, CLOCK_MONOTONIC ns, and its thread CPU time (ns).
struct TickTimes {
  int64_t scheduled_ns = 0;  // when it should have started
  int64_t wake_ns = 0;       // when it started
  int64_t end_ns = 0;        // after the wrench was handed over
  int64_t deadline_ns = 0;   // the next tick's start
  int64_t cpu_ns = 0;        // the thread's CPU time over the tick
};

class MissClassifier {
 public:
  explicit MissClassifier(int64_t period_ns) : period_ns_(period_ns) {}

  // Every tick, in order (ticks that fit are the witnesses). work: the
  // tick's counted work (any unit that grows with its cost), < 0: not counted.
  MissCause Classify(const TickTimes& t, int64_t work);

  // Most work of a counted tick that ran in half a period of CPU time (-1: none yet).
  int64_t max_witness_work() const { return max_witness_work_; }

 private:
  int64_t period_ns_;
  int64_t max_witness_work_ = -1;
};

}  // namespace haptics
