#pragma once
// Wakes the servo thread when a pose arrives (pose-triggered tick,
// servo_loop.h): a 32-bit arrival counter that the receive thread bumps after
// handing a pose over (Notify: an atomic increment and a futex wake, on the
// receive thread), and that the servo thread waits on with an absolute
// CLOCK_MONOTONIC deadline (WaitUntil: the one sleeping syscall the tick
// already had). No lock: the futex only sleeps while the counter still holds
// the value the waiter saw, so a pose that arrives between the check and the
// sleep is never missed.
#include <atomic>
#include <cstdint>

namespace haptics {

class ArrivalSignal {
 public:
  // Receive side: after the pose is published.
  void Notify();
  // Servo side: the counter now (read it before checking for a new pose).
  uint32_t count() const { return count_.load(std::memory_order_acquire); }
  // Sleeps until the counter differs from `seen` or CLOCK_MONOTONIC reaches
  // deadline_ns. Returns true if woken by an arrival (or it had already come).
  bool WaitUntil(uint32_t seen, int64_t deadline_ns);

 private:
  std::atomic<uint32_t> count_{0};
};

}  // namespace haptics
