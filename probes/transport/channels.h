#pragma once
// Default LCM channel names, the same as haptic_server's defaults.
namespace probes {

inline constexpr const char* kDefaultPoseChannel = "PROBE_POSE";
inline constexpr const char* kDefaultWrenchChannel = "HAPTIC_WRENCH";
inline constexpr const char* kDefaultStatusChannel = "HAPTIC_STATUS";

}  // namespace probes
