#pragma once
// Phase lock of the fixed-rate servo tick to pose arrival.
//
// The device (here: probe_replay) sends a pose every period on its own clock.
// A free-running 1 kHz loop takes it at its next tick, after a wait anywhere
// in [0, T) set by the phase between the two clocks: up to a whole period of
// added latency, different on every run. PhaseLock keeps the loop at its
// fixed rate but nudges the tick schedule so that the newest pose has waited
// about `target_us` when a tick takes it:
//   shift = clamp(-gain * (wait - target), -max_step, +max_step)
// added to the next deadline. The clamp bounds the period change, so the
// loop's rate stays within max_step / T of nominal while it locks. A pose
// that just missed a tick (wait near T) moves the schedule by at most
// max_step; in steady state the tick sits target_us after the typical arrival,
// which leaves that much room for transport jitter before a pose misses it.
// Times in microseconds. Pure arithmetic, no clock: the servo loop feeds it.
#include <cstdint>

namespace haptics {

struct PhaseLockOptions {
  bool enabled = true;
  double target_us = 150.0;  // wanted wait from pose receipt to the tick taking it
  double gain = 0.1;         // fraction of the error corrected per tick
  double max_step_us = 5.0;  // largest deadline shift per tick
};

class PhaseLock {
 public:
  PhaseLock(const PhaseLockOptions& options, double period_us);

  // `wait_us`: receipt-to-wake time of the pose this tick took (fixed-rate
  // ticks), or the pose's lead on the deadline (pose-triggered ticks, may be
  // negative). Returns the shift (us) to add to the next deadline; negative:
  // tick earlier.
  double Update(double wait_us);

  const PhaseLockOptions& options() const { return options_; }
  int64_t updates() const { return updates_; }
  int64_t clamped() const { return clamped_; }  // updates limited by max_step
  double last_wait_us() const { return last_wait_us_; }

 private:
  PhaseLockOptions options_;
  double period_us_;
  int64_t updates_ = 0;
  int64_t clamped_ = 0;
  double last_wait_us_ = 0.0;
};

}  // namespace haptics
