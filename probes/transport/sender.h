#pragma once
// Who a probe client is on the pose channel (probe_pose_t version 2): a
// session id drawn at random when the client starts (or given with
// --session, e.g. to match a server's --accept-session) and a device name.
// The server renders one sender at a time; see msgs/README.md.
#include <cstdint>
#include <string>

#include "msgs/sender_identity.h"
#include "probes/trajectory/input_error.h"

namespace probes {

struct Sender {
  int64_t session = 0;  // non-zero
  std::string device;   // at most haptics_msgs::kMaxDeviceNameBytes
  std::string Describe() const { return haptics_msgs::FormatSession(session) + " '" + device + "'"; }
};

// session_text: "" draws a new random session; else 0x-prefixed hex or
// decimal, non-zero. Throws InputError naming the option and value.
inline Sender MakeSender(const std::string& session_text, const std::string& device) {
  Sender s;
  s.device = device;
  if (session_text.empty()) {
    s.session = haptics_msgs::NewSession();
  } else if (!haptics_msgs::ParseSession(session_text, &s.session)) {
    throw InputError("--session: '" + session_text +
                     "' is not a non-zero 64-bit session id (0x-prefixed hex or decimal)");
  }
  if (device.size() > haptics_msgs::kMaxDeviceNameBytes)
    throw InputError("--device: '" + device + "' is longer than 64 bytes");
  return s;
}

}  // namespace probes
