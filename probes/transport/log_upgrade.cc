#include "probes/transport/log_upgrade.h"

#include <lcm/lcm-cpp.hpp>
#include <vector>

#include "haptics_msgs/probe_pose_t.hpp"
#include "haptics_msgs/probe_pose_v1_t.hpp"
#include "probes/trajectory/input_error.h"

namespace probes {
namespace {

haptics_msgs::probe_pose_t Upgrade(const haptics_msgs::probe_pose_v1_t& v1, const Sender& sender) {
  haptics_msgs::probe_pose_t v2{};
  v2.version = haptics_msgs::probe_pose_t::VERSION;
  v2.sender_session = sender.session;
  v2.sender_device = sender.device;
  v2.utime = v1.utime;
  v2.seq = v1.seq;
  for (int i = 0; i < 3; ++i) v2.position[i] = v1.position[i];
  for (int i = 0; i < 4; ++i) v2.orientation[i] = v1.orientation[i];
  v2.has_velocity = v1.has_velocity;
  for (int i = 0; i < 3; ++i) v2.linear_velocity[i] = v1.linear_velocity[i];
  for (int i = 0; i < 3; ++i) v2.angular_velocity[i] = v1.angular_velocity[i];
  return v2;
}

}  // namespace

LogUpgradeCounts UpgradePoseLog(const std::string& in_path, const std::string& out_path,
                                const std::string& pose_channel, const Sender& sender) {
  lcm::LogFile in(in_path, "r");
  if (!in.good()) throw InputError(in_path + ": cannot open LCM log");
  lcm::LogFile out(out_path, "w");
  if (!out.good()) throw InputError(out_path + ": cannot open for writing");
  LogUpgradeCounts n;
  int64_t index = 0;
  std::vector<uint8_t> buffer;
  for (const lcm::LogEvent* e = in.readNextEvent(); e != nullptr; e = in.readNextEvent()) {
    ++index;
    lcm::LogEvent copy = *e;
    if (e->channel == pose_channel) {
      haptics_msgs::probe_pose_v1_t v1;
      haptics_msgs::probe_pose_t v2;
      if (v1.decode(e->data, 0, e->datalen) == e->datalen) {
        const haptics_msgs::probe_pose_t pose = Upgrade(v1, sender);
        buffer.resize(pose.getEncodedSize());
        pose.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
        copy.data = buffer.data();
        copy.datalen = static_cast<int32_t>(buffer.size());
        ++n.upgraded;
      } else if (v2.decode(e->data, 0, e->datalen) == e->datalen) {
        ++n.already;
      } else {
        throw InputError(in_path + ": event " + std::to_string(index) + " on '" + pose_channel +
                         "' is neither probe_pose_t version 1 nor version 2 (" + std::to_string(e->datalen) +
                         " bytes)");
      }
    } else {
      ++n.copied;
    }
    if (out.writeEvent(&copy) != 0) throw InputError(out_path + ": write failed");
  }
  if (n.upgraded + n.already == 0) throw InputError(in_path + ": no pose on channel '" + pose_channel + "'");
  return n;
}

}  // namespace probes
