#pragma once
// Reads probe poses from an LCM log file (written by lcm-logger or
// probe_recorder). Only events on the pose channel are used; LCM_SELF_TEST
// events (written by the udpm provider at start) and other channels are
// skipped. Sample times come from the poses' own utime, so the replay keeps
// the sender's timing rather than the logger's receive timing.
#include <string>

#include "probes/pose_sample.h"

namespace probes {

// True if the file starts with the LCM log event magic number.
bool IsLcmLogFile(const std::string& path);

// Throws InputError naming the file and event number on an undecodable pose,
// non-increasing utime, non-finite value, or when the channel holds no pose.
Trajectory ReadTrajectoryLcmLog(const std::string& path, const std::string& pose_channel);

}  // namespace probes
