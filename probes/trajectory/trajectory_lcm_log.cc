#include "probes/trajectory/trajectory_lcm_log.h"

#include <cmath>
#include <cstdint>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>

#include "haptics_msgs/probe_pose_t.hpp"
#include "haptics_msgs/probe_pose_v1_t.hpp"
#include "msgs/sender_identity.h"
#include "probes/trajectory/input_error.h"

namespace probes {
namespace {

constexpr uint32_t kLcmLogMagic = 0xEDA1DA01;  // big-endian, first word of every event

bool AllFinite(const double* v, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

}  // namespace

bool IsLcmLogFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char b[4] = {0, 0, 0, 0};
  if (!in.read(reinterpret_cast<char*>(b), 4)) return false;
  const uint32_t word = (uint32_t{b[0]} << 24) | (uint32_t{b[1]} << 16) |
                        (uint32_t{b[2]} << 8) | uint32_t{b[3]};
  return word == kLcmLogMagic;
}

Trajectory ReadTrajectoryLcmLog(const std::string& path, const std::string& pose_channel,
                                int64_t session) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw InputError(path + ": cannot open LCM log");

  Trajectory trajectory;
  const bool session_given = session != 0;
  std::map<std::string, int> other_channels;
  std::map<int64_t, std::pair<std::string, int>> senders;  // session -> device, poses
  int64_t first_utime = 0;
  int64_t previous_utime = 0;
  int event_index = 0;
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
    ++event_index;
    if (e->channel != pose_channel) {
      if (e->channel != "LCM_SELF_TEST") ++other_channels[e->channel];
      continue;
    }
    const std::string where = path + ": event " + std::to_string(event_index) +
                              " (eventnum " + std::to_string(e->eventnum) + ") on '" +
                              pose_channel + "'";
    haptics_msgs::probe_pose_t msg{};
    if (msg.decode(e->data, 0, e->datalen) != e->datalen) {
      haptics_msgs::probe_pose_v1_t v1{};
      if (v1.decode(e->data, 0, e->datalen) == e->datalen) {
        throw InputError(where + ": a probe_pose_t version 1 pose (no sender identity): the log "
                         "predates version " + std::to_string(haptics_msgs::probe_pose_t::VERSION) +
                         "; convert it with `probe_log_upgrade --in " + path +
                         " --out NEW.lcmlog` (probes/README.md)");
      }
      throw InputError(where + ": cannot decode as haptics_msgs.probe_pose_t (" +
                       std::to_string(e->datalen) + " bytes)");
    }
    if (msg.version != haptics_msgs::probe_pose_t::VERSION) {
      throw InputError(where + ": probe_pose_t version " + std::to_string(msg.version) +
                       ", this build reads version " +
                       std::to_string(haptics_msgs::probe_pose_t::VERSION));
    }
    auto& [device, count] = senders[msg.sender_session];
    if (count++ == 0) device = msg.sender_device;
    if (session == 0 && senders.size() == 1) session = msg.sender_session;
    if (msg.sender_session != session) continue;
    if (!AllFinite(msg.position, 3) || !AllFinite(msg.orientation, 4) ||
        (msg.has_velocity &&
         (!AllFinite(msg.linear_velocity, 3) || !AllFinite(msg.angular_velocity, 3)))) {
      throw InputError(where + ": pose seq " + std::to_string(msg.seq) +
                       " has a non-finite value");
    }
    const double norm = std::sqrt(msg.orientation[0] * msg.orientation[0] +
                                  msg.orientation[1] * msg.orientation[1] +
                                  msg.orientation[2] * msg.orientation[2] +
                                  msg.orientation[3] * msg.orientation[3]);
    if (std::abs(norm - 1.0) > 1e-3) {
      throw InputError(where + ": pose seq " + std::to_string(msg.seq) +
                       " orientation has norm " + std::to_string(norm) + ", not within 1e-3 of 1");
    }
    if (trajectory.empty()) {
      first_utime = msg.utime;
    } else if (msg.utime <= previous_utime) {
      throw InputError(where + ": utime " + std::to_string(msg.utime) +
                       " us does not increase (previous " + std::to_string(previous_utime) + ")");
    }
    previous_utime = msg.utime;

    PoseSample s;
    s.t = 1e-6 * static_cast<double>(msg.utime - first_utime);
    for (int i = 0; i < 3; ++i) s.p_WP[i] = msg.position[i];
    for (int i = 0; i < 4; ++i) s.q_WP[i] = msg.orientation[i] / norm;
    s.has_velocity = msg.has_velocity;
    if (s.has_velocity) {
      for (int i = 0; i < 3; ++i) s.v_WP[i] = msg.linear_velocity[i];
      for (int i = 0; i < 3; ++i) s.w_WP[i] = msg.angular_velocity[i];
    }
    trajectory.push_back(s);
  }
  if (senders.size() > 1 && !session_given) {
    std::string list;
    for (const auto& [id, who] : senders) {
      list += (list.empty() ? "" : ", ") + haptics_msgs::FormatSession(id) + " '" + who.first + "' (" +
              std::to_string(who.second) + " poses)";
    }
    throw InputError(path + ": pose channel '" + pose_channel + "' holds " + std::to_string(senders.size()) +
                     " senders: " + list + "; choose one with --log-session");
  }
  if (trajectory.empty() && session_given && !senders.empty()) {
    throw InputError(path + ": no pose of sender " + haptics_msgs::FormatSession(session) +
                     " on pose channel '" + pose_channel + "' (" + std::to_string(senders.size()) +
                     " other senders)");
  }
  if (trajectory.empty()) {
    std::string seen;
    for (const auto& [channel, count] : other_channels) {
      seen += (seen.empty() ? "" : ", ") + channel + " (" + std::to_string(count) + ")";
    }
    throw InputError(path + ": no events on pose channel '" + pose_channel +
                     "'; channels in the log: " + (seen.empty() ? "none" : seen));
  }
  return trajectory;
}

}  // namespace probes
