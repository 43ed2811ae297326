// probe_log_upgrade: converts an LCM log recorded before probe_pose_t
// version 2 (no sender identity) so that probe_replay reads it again
// (probes/transport/log_upgrade.h): every version-1 pose on the pose channel becomes a
// version-2 pose of one sender (--session, random by default, and
// --device), all other fields unchanged; every other event is copied byte
// for byte.
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
#include <string>

#include "probes/transport/channels.h"
#include "probes/transport/log_upgrade.h"
#include "probes/transport/sender.h"

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
    const probes::Sender sender = probes::MakeSender(session_text, device);
    const probes::LogUpgradeCounts n = probes::UpgradePoseLog(in_path, out_path, channel, sender);
    std::printf("probe_log_upgrade: %s -> %s: %lld version-1 poses now from sender %s, %lld already "
                "version 2, %lld other events copied\n",
                in_path.c_str(), out_path.c_str(), static_cast<long long>(n.upgraded), sender.Describe().c_str(),
                static_cast<long long>(n.already), static_cast<long long>(n.copied));
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "probe_log_upgrade: " << e.what() << "\n";
    return 1;
  }
}
