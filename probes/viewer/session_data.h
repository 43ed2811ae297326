#pragma once
// A recorded haptic session as the viewer uses it: per probe pose sent, the
// device pose and the server's answer. Read from probe_replay's result CSV
// or from an LCM log of poses and wrenches (read_session.h). SI units; poses
// of the device frame D in world W, quaternions w, x, y, z; the wrench acts
// on the device at its reference point, in W.
#include <cstdint>
#include <string>
#include <vector>

#include "pd_core/geometry/pose.h"

namespace probes {

struct SessionFrame {
  double t = 0.0;            // session time (s) from the first pose
  int64_t seq = -1;          // pose seq
  int64_t send_us = 0;       // sender's CLOCK_MONOTONIC send time (us)
  pd::Vector3 p_WD = pd::Vector3::Zero();
  pd::Quaternion q_WD = pd::Quaternion::Identity();
  bool answered = false;     // the fields below hold the server's answer
  pd::Vector3 f_W = pd::Vector3::Zero();    // N
  pd::Vector3 tau_W = pd::Vector3::Zero();  // N·m
  double depth = 0.0;        // deepest PD this tick (m)
  int contact_count = 0;     // contact regions
  int flags = 0;             // wrench_t flags
  double round_trip_us = -1.0;  // -1: unknown
};

struct Session {
  std::string source;   // the file it was read from
  std::string format;   // "result-csv" or "lcm-log"
  std::vector<SessionFrame> frames;  // poses in send order
};

}  // namespace probes
