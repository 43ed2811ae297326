#pragma once
// Per-pose result CSV of a replay, one row per planned pose, columns:
//   seq,t,send_utime,x,y,z,qw,qx,qy,qz,answered,answers,
//   fx,fy,fz,tx,ty,tz,flags,penetration_depth,contact_count,latency_us
// t is the trajectory time (s), send_utime the replay's CLOCK_MONOTONIC send
// time (µs; empty if never sent). Wrench columns hold the first answer
// (force N and torque N·m in world W, depth m); they are empty when the pose
// was not answered (answered = 0). latency_us = receive - send time.
#include <iosfwd>
#include <vector>

#include "probes/trajectory/pose_sample.h"
#include "probes/results/seq_matcher.h"

namespace probes {

inline constexpr const char* kResultCsvHeader =
    "seq,t,send_utime,x,y,z,qw,qx,qy,qz,answered,answers,fx,fy,fz,tx,ty,tz,flags,"
    "penetration_depth,contact_count,latency_us";

// records[i] must belong to trajectory[i]; throws std::invalid_argument otherwise.
void WriteResultCsv(std::ostream& out, const Trajectory& trajectory,
                    const std::vector<PoseRecord>& records);

}  // namespace probes
