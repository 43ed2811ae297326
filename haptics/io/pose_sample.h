#pragma once
// One probe (device handle) pose as received, before validation. The device
// frame D is the probe frame P of haptics_msgs::probe_pose_t.
#include <cstdint>

#include "haptics/tool/spatial.h"

namespace haptics {

struct PoseSample {
  int64_t seq = -1;    // sender's sequence number, echoed in the wrench
  int64_t utime = 0;   // sender's CLOCK_MONOTONIC time of the sample (us)
  int64_t session = 0; // sender_session of the stream it belongs to (pose_source_lock.h)
  Vector3 p_WD = Vector3::Zero();                    // m
  Quaternion q_WD = Quaternion::Identity();          // as received: not normalised
  bool has_velocity = false;                         // the two below are measured
  Vector3 v_WD = Vector3::Zero();                    // m/s
  Vector3 w_WD = Vector3::Zero();                    // rad/s
  int64_t receive_time_ns = 0;  // server CLOCK_MONOTONIC at receipt (ns)
};

}  // namespace haptics
