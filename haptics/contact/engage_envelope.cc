#include "haptics/contact/engage_envelope.h"

#include <algorithm>

#include "haptics/io/wrench_output.h"

namespace haptics {

EngageEnvelope::EngageEnvelope(double soft_engage_s, double watchdog_timeout_s,
                               double watchdog_ramp_s)
    : soft_engage_s_(soft_engage_s), watchdog_timeout_s_(watchdog_timeout_s),
      watchdog_ramp_s_(watchdog_ramp_s) {}

double EngageEnvelope::Update(double t, bool fresh_pose, int32_t* flags) {
  if (!engaged_) {
    if (!fresh_pose) return 0.0;
    // First valid pose: the ramp starts at zero now.
    engaged_ = true;
    last_t_ = t;
    last_fresh_t_ = t;
    scale_ = soft_engage_s_ > 0.0 ? 0.0 : 1.0;
    if (scale_ < 1.0) *flags |= kFlagSoftEngage;
    return scale_;
  }
  const double dt = std::max(0.0, t - last_t_);
  last_t_ = t;
  if (fresh_pose) last_fresh_t_ = t;
  const bool stale_too_long = t - last_fresh_t_ > watchdog_timeout_s_;
  if (stale_too_long) {
    if (!watchdog_) ++watchdog_trips_;
    watchdog_ = true;
    scale_ = std::max(0.0, scale_ - dt / watchdog_ramp_s_);
    *flags |= kFlagWatchdog;
  } else {
    watchdog_ = false;
    scale_ = soft_engage_s_ > 0.0 ? std::min(1.0, scale_ + dt / soft_engage_s_) : 1.0;
    if (scale_ < 1.0) *flags |= kFlagSoftEngage;
  }
  return scale_;
}

}  // namespace haptics
