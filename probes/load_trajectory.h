#pragma once
// Loads a trajectory from either format, chosen by content, not by name: an
// LCM log starts with its event magic number, anything else is read as CSV.
#include <string>

#include "probes/pose_sample.h"

namespace probes {

Trajectory LoadTrajectory(const std::string& path, const std::string& pose_channel);

}  // namespace probes
