#pragma once
// Conditions the wrench before it goes to the device, in this order:
//  1. multiply by the engage/watchdog scale;
//  2. clamp |f| to max_force and |tau| to max_torque, keeping directions
//     (FLAG_FORCE_SATURATED / FLAG_TORQUE_SATURATED, counted);
//  3. limit the change from the previous output to max_force_rate * dt and
//     max_torque_rate * dt, again keeping the direction of the change
//     (FLAG_RATE_LIMITED, counted): bounded jerk when PD switches;
//  4. a final guard: any non-finite component zeroes the whole wrench
//     (counted), so no NaN or inf ever reaches the device.
// Steps 2-3 keep the output within the limits: it moves from the previous
// output (within limits) toward a target within limits.
#include <cstdint>

#include "haptics/scene/scene_config.h"
#include "haptics/tool/spatial.h"

namespace haptics {

struct LimiterCounts {
  int64_t force_saturated = 0;   // ticks
  int64_t torque_saturated = 0;  // ticks
  int64_t saturated = 0;         // ticks with force or torque clamped
  int64_t rate_limited = 0;      // ticks
  int64_t nonfinite = 0;         // outputs replaced by zero
};

class WrenchLimiter {
 public:
  // dt: the servo period (s).
  WrenchLimiter(const DeviceConfig& device, double dt);

  // Returns the conditioned wrench; ORs the flags it raised into *flags.
  Wrench Apply(const Wrench& raw, double scale, int32_t* flags);

  // Previous output back to zero (the rate limit starts from rest).
  void Reset() { previous_ = Wrench{}; }

  const Wrench& previous() const { return previous_; }
  const LimiterCounts& counts() const { return counts_; }

 private:
  double max_force_, max_torque_, max_df_, max_dtau_;
  Wrench previous_;
  LimiterCounts counts_;
};

}  // namespace haptics
