#pragma once
// Reads probe poses from an LCM log file (written by lcm-logger or
// probe_recorder). Only events on the pose channel are used; LCM_SELF_TEST
// events (written by the udpm provider at start) and other channels are
// skipped. Sample times come from the poses' own utime, so the replay keeps
// the sender's timing rather than the logger's receive timing.
#include <cstdint>
#include <string>

#include "probes/trajectory/pose_sample.h"

namespace probes {

// True if the file starts with the LCM log event magic number.
bool IsLcmLogFile(const std::string& path);

// Poses are probe_pose_t version 2 (msgs/README.md). A log recorded while
// several senders published holds several streams: `session` picks one (its
// poses only); with session 0 the log must hold exactly one sender.
// Throws InputError naming the file and event number on an undecodable pose
// (a version-1 pose names the converter, probe_log_upgrade), another
// version, non-increasing utime, non-finite value, when the channel holds no
// pose of the sender, or (session 0) when it holds several senders, listed.
Trajectory ReadTrajectoryLcmLog(const std::string& path, const std::string& pose_channel,
                                int64_t session = 0);

}  // namespace probes
