#pragma once
// Loads a trajectory from either format, chosen by content, not by name: an
// LCM log starts with its event magic number, anything else is read as CSV.
#include <cstdint>
#include <string>

#include "probes/trajectory/pose_sample.h"

namespace probes {

// session: for an LCM log, the sender whose poses to use (0: the log's only
// sender; see ReadTrajectoryLcmLog).
Trajectory LoadTrajectory(const std::string& path, const std::string& pose_channel, int64_t session = 0);

}  // namespace probes
