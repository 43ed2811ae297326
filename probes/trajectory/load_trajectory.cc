#include "probes/trajectory/load_trajectory.h"

#include "probes/trajectory/trajectory_csv.h"
#include "probes/trajectory/trajectory_lcm_log.h"

namespace probes {

Trajectory LoadTrajectory(const std::string& path, const std::string& pose_channel, int64_t session) {
  if (IsLcmLogFile(path)) return ReadTrajectoryLcmLog(path, pose_channel, session);
  return ReadTrajectoryCsv(path);
}

}  // namespace probes
