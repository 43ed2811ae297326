// probe_log_upgrade: converts an LCM log recorded before probe_pose_t
// version 2 (no sender identity) so that probe_replay and the server's tools
// read it again. Every version-1 pose on the pose channel becomes a version-2
// pose of one sender (--session, random by default, and --device), all
// other fields unchanged; every other event (other channels, LCM_SELF_TEST)
// is copied byte for byte. Old wrench_t / server_status_t events stay in
// their old format (nothing here reads them back).
//
//   probe_log_upgrade --in OLD.lcmlog --out NEW.lcmlog [--pose-channel C]
//                     [--session ID] [--device NAME]
//
// Exit codes: 0 converted; 1 bad input (unreadable log, an event on the
// pose channel that is neither version 1 nor version 2, no pose at all,
// output not writable).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "haptics_msgs/probe_pose_t.hpp"
#include "haptics_msgs/probe_pose_v1_t.hpp"
#include "probes/channels.h"
#include "probes/input_error.h"
#include "probes/sender.h"

namespace {

haptics_msgs::probe_pose_t Upgrade(const haptics_msgs::probe_pose_v1_t& v1, const probes::Sender& sender) {
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

int Convert(const std::string& in_path, const std::string& out_path, const std::string& channel,
            const probes::Sender& sender) {
  lcm::LogFile in(in_path, "r");
  if (!in.good()) throw probes::InputError(in_path + ": cannot open LCM log");
  lcm::LogFile out(out_path, "w");
  if (!out.good()) throw probes::InputError(out_path + ": cannot open for writing");
  int64_t upgraded = 0, already = 0, copied = 0, index = 0;
  std::vector<uint8_t> buffer;
  for (const lcm::LogEvent* e = in.readNextEvent(); e != nullptr; e = in.readNextEvent()) {
    ++index;
    lcm::LogEvent copy = *e;
    if (e->channel == channel) {
      haptics_msgs::probe_pose_v1_t v1;
      haptics_msgs::probe_pose_t v2;
      if (v1.decode(e->data, 0, e->datalen) == e->datalen) {
        const haptics_msgs::probe_pose_t pose = Upgrade(v1, sender);
        buffer.resize(pose.getEncodedSize());
        pose.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
        copy.data = buffer.data();
        copy.datalen = static_cast<int32_t>(buffer.size());
        ++upgraded;
      } else if (v2.decode(e->data, 0, e->datalen) == e->datalen) {
        ++already;  // mixed or already converted: kept as it is
      } else {
        throw probes::InputError(in_path + ": event " + std::to_string(index) + " on '" + channel +
                                 "' is neither probe_pose_t version 1 nor version 2 (" +
                                 std::to_string(e->datalen) + " bytes)");
      }
    } else {
      ++copied;
    }
    if (out.writeEvent(&copy) != 0) throw probes::InputError(out_path + ": write failed");
  }
  if (upgraded + already == 0) throw probes::InputError(in_path + ": no pose on channel '" + channel + "'");
  std::printf("probe_log_upgrade: %s -> %s: %lld version-1 poses now from sender %s, %lld already "
              "version 2, %lld other events copied\n",
              in_path.c_str(), out_path.c_str(), static_cast<long long>(upgraded), sender.Describe().c_str(),
              static_cast<long long>(already), static_cast<long long>(copied));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"probe_log_upgrade: converts a probe_pose_t version-1 LCM log (no sender identity) to version 2"};
  std::string in_path, out_path, channel = probes::kDefaultPoseChannel, session_text, device = "upgraded_log";
  app.add_option("--in", in_path, "LCM log with version-1 poses")->required()->check(CLI::ExistingFile);
  app.add_option("--out", out_path, "LCM log to write")->required();
  app.add_option("--pose-channel", channel)->capture_default_str();
  app.add_option("--session", session_text, "sender session of the converted poses (default: random)");
  app.add_option("--device", device, "sender device name of the converted poses")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return Convert(in_path, out_path, channel, probes::MakeSender(session_text, device));
  } catch (const std::exception& e) {
    std::cerr << "probe_log_upgrade: " << e.what() << "\n";
    return 1;
  }
}
