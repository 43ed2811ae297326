#pragma once
// The force scale in [0, 1] that multiplies the rendered wrench:
//  - soft engage: from the first valid pose the scale ramps linearly 0 -> 1
//    over soft_engage_s (FLAG_SOFT_ENGAGE while below 1), so the device does
//    not kick when the server starts with the tool in contact;
//  - watchdog: when no valid pose has arrived for more than
//    watchdog_timeout_s, the scale ramps linearly to 0 over watchdog_ramp_s
//    (FLAG_WATCHDOG); when poses resume it ramps up again at the soft-engage
//    rate.
// Times are the servo loop's clock (s).
#include <cstdint>

namespace haptics {

class EngageEnvelope {
 public:
  // soft_engage_s >= 0 (0: immediate), watchdog_timeout_s > 0, watchdog_ramp_s > 0.
  EngageEnvelope(double soft_engage_s, double watchdog_timeout_s, double watchdog_ramp_s);

  // One tick at time t; fresh_pose: a valid pose arrived this tick. Returns
  // the scale and ORs kFlagSoftEngage / kFlagWatchdog into *flags.
  double Update(double t, bool fresh_pose, int32_t* flags);

  // Back to not engaged: the next fresh pose starts the soft engage from
  // zero (a new device stream taking over must not inherit any force).
  void Restart() { engaged_ = false; watchdog_ = false; scale_ = 0.0; }

  double scale() const { return scale_; }
  bool engaged() const { return engaged_; }        // a valid pose has been seen
  bool watchdog_active() const { return watchdog_; }
  int64_t watchdog_trips() const { return watchdog_trips_; }

 private:
  double soft_engage_s_, watchdog_timeout_s_, watchdog_ramp_s_;
  bool engaged_ = false;
  bool watchdog_ = false;
  double scale_ = 0.0;
  double last_t_ = 0.0;
  double last_fresh_t_ = 0.0;
  int64_t watchdog_trips_ = 0;
};

}  // namespace haptics
