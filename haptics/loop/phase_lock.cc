#include "haptics/loop/phase_lock.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace haptics {

PhaseLock::PhaseLock(const PhaseLockOptions& options, double period_us)
    : options_(options), period_us_(period_us) {
  if (!(period_us > 0.0) || !(options.target_us >= 0.0) || !(options.target_us < period_us) ||
      !(options.gain > 0.0 && options.gain <= 1.0) || !(options.max_step_us >= 0.0) ||
      !(options.max_step_us < 0.1 * period_us))
    throw std::invalid_argument(
        "phase lock: need 0 <= target_us < period (" + std::to_string(period_us) +
        " us), 0 < gain <= 1 and 0 <= max_step_us < 10% of the period; got target_us " +
        std::to_string(options.target_us) + ", gain " + std::to_string(options.gain) +
        ", max_step_us " + std::to_string(options.max_step_us));
}

double PhaseLock::Update(double wait_us) {
  // Negative: the pose came after the deadline (pose-triggered ticks measure
  // the pose's lead on the deadline, which may be either side of it).
  if (!options_.enabled || !std::isfinite(wait_us)) return 0.0;
  ++updates_;
  last_wait_us_ = wait_us;
  const double want = -options_.gain * (wait_us - options_.target_us);
  const double shift = std::clamp(want, -options_.max_step_us, options_.max_step_us);
  if (shift != want) ++clamped_;
  return shift;
}

}  // namespace haptics
