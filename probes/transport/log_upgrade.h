#pragma once
// Converts an LCM log recorded before probe_pose_t version 2 (no sender
// identity; msgs/README.md) so that probe_replay reads it again: every
// version-1 pose on the pose channel becomes a version-2 pose of one sender,
// all other fields unchanged; version-2 poses and every other event
// (other channels, LCM_SELF_TEST) are copied byte for byte, in order. Old
// wrench_t / server_status_t events keep their old format: nothing reads
// them back. The probe_log_upgrade tool is this function.
#include <cstdint>
#include <string>

#include "probes/transport/sender.h"

namespace probes {

struct LogUpgradeCounts {
  int64_t upgraded = 0;  // version-1 poses converted
  int64_t already = 0;   // version-2 poses kept
  int64_t copied = 0;    // other events copied
};

// Throws InputError naming the file (and event) for an unreadable input, an
// unwritable output, an event on the pose channel that is neither version 1
// nor version 2, or a log without any pose.
LogUpgradeCounts UpgradePoseLog(const std::string& in_path, const std::string& out_path,
                                const std::string& pose_channel, const Sender& sender);

}  // namespace probes
