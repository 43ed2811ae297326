#pragma once
// Fills a probe_pose_t from a trajectory sample. utime is the sender's
// CLOCK_MONOTONIC time at publication (µs), not the trajectory time: the
// server echoes it and the wrench's pose_utime then timestamps the round trip.
// Every pose carries the sender's identity (msgs/README.md, version 2).
#include <cstdint>

#include "haptics_msgs/probe_pose_t.hpp"
#include "probes/trajectory/pose_sample.h"
#include "probes/transport/sender.h"

namespace probes {

inline haptics_msgs::probe_pose_t MakePoseMessage(const PoseSample& s, int64_t seq, int64_t utime,
                                                  const Sender& sender) {
  haptics_msgs::probe_pose_t msg{};
  msg.version = haptics_msgs::probe_pose_t::VERSION;
  msg.sender_session = sender.session;
  msg.sender_device = sender.device;
  msg.utime = utime;
  msg.seq = seq;
  for (int i = 0; i < 3; ++i) msg.position[i] = s.p_WP[i];
  for (int i = 0; i < 4; ++i) msg.orientation[i] = s.q_WP[i];
  msg.has_velocity = s.has_velocity;
  for (int i = 0; i < 3; ++i) msg.linear_velocity[i] = s.has_velocity ? s.v_WP[i] : 0.0;
  for (int i = 0; i < 3; ++i) msg.angular_velocity[i] = s.has_velocity ? s.w_WP[i] : 0.0;
  return msg;
}

}  // namespace probes
