#pragma once
// What the servo loop sends each tick: the wrench the device should render
// and why it looks the way it does. Mirrors haptics_msgs::wrench_t.
#include <cstdint>

#include "haptics/tool/spatial.h"

namespace haptics {

// Bits of WrenchOutput::flags; equal to the wrench_t.lcm constants (checked
// where the message is filled).
inline constexpr int32_t kFlagForceSaturated = 1;   // force clamped to the device limit
inline constexpr int32_t kFlagTorqueSaturated = 2;  // torque clamped to the device limit
inline constexpr int32_t kFlagRateLimited = 4;      // force or torque change clamped by its max rate
inline constexpr int32_t kFlagWatchdog = 8;         // no pose within the watchdog time: ramping to zero
inline constexpr int32_t kFlagStaleInput = 16;      // no new valid pose since the previous tick
inline constexpr int32_t kFlagSoftEngage = 32;      // start-up (or recovery) ramp in progress
inline constexpr int32_t kFlagPdInvalid = 64;       // a pair's newest PD answer could not be verified
inline constexpr int32_t kFlagContactHeld = 128;    // ... and its last valid contact is held (decaying)
inline constexpr int32_t kFlagModelStale = 256;     // contact model older than contact.model_max_age_ms: ramping out

struct WrenchOutput {
  int64_t tick = 0;         // server tick number
  int64_t pose_seq = -1;    // seq of the newest accepted pose (-1: none yet)
  int64_t pose_utime = 0;   // its utime, echoed for round-trip timing (us)
  int64_t pose_session = 0; // its sender session: whose stream is rendered (0: none yet)
  // On the device, at the device/tool reference point, in W: the virtual
  // coupling's reaction after conditioning.
  Wrench wrench;
  double penetration_depth = 0.0;  // deepest PD over scene objects (m)
  int32_t contact_count = 0;       // contact regions summed over objects
  double solver_time_us = 0.0;     // renderer time this tick (us)
  int32_t flags = 0;               // kFlag* bits
};

}  // namespace haptics
