#pragma once
// One device, one pose stream. Every probe pose names its sender
// (probe_pose_t.sender_session, a random non-zero 64-bit id the client draws
// at start, and sender_device, its device name). The server renders one
// sender at a time:
//  - it locks onto the first sender whose pose is valid (pose_validation.h);
//  - while that stream is alive, poses from any other sender are rejected
//    (counted; the caller logs each new sender once);
//  - the stream stays alive while its valid poses keep coming; once it has
//    been silent for `release_after` (the watchdog timeout plus the ramp plus
//    two servo periods, see MakePoseSourceOptions in lcm_io.h: the force
//    has gone to zero) the next valid sender takes over;
//  - an optional pin accepts only a given session and/or device name, so a
//    stray client can never take over even when the device is silent.
// A sender that changes its session (or device name) is a new sender: a
// restarted client does not silently continue the old stream.
// Pure logic on the receive thread: times are passed in, no allocation per
// pose (the table of senders seen is fixed-size).
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "msgs/sender_identity.h"

namespace haptics {

using haptics_msgs::kMaxDeviceNameBytes;  // bytes of probe_pose_t.sender_device

// A sender's identity, fixed-size so that it can be copied without allocating.
struct SenderId {
  int64_t session = 0;                                  // 0: no identity
  std::array<char, kMaxDeviceNameBytes + 1> device{};  // NUL-terminated

  // device must be at most kMaxDeviceNameBytes (longer names are cut).
  static SenderId Make(int64_t session, std::string_view device);
  std::string_view device_name() const { return std::string_view(device.data()); }
  bool operator==(const SenderId& o) const {
    return session == o.session && device_name() == o.device_name();
  }
  bool operator!=(const SenderId& o) const { return !(*this == o); }
};

// Which senders may be rendered at all (--accept-session / --accept-device).
struct PoseSourcePin {
  int64_t session = 0;  // 0: any session
  std::string device;   // empty: any device
  bool active() const { return session != 0 || !device.empty(); }
  bool Accepts(const SenderId& s) const {
    return (session == 0 || s.session == session) && (device.empty() || s.device_name() == device);
  }
};

enum class SourceDecision {
  kAccept,             // render it (the locked stream, or no stream locked yet)
  kLocked,             // render it: this pose locked its sender (first or takeover)
  kRejectOtherSender,  // another sender holds the lock and is alive
  kRejectNotPinned,    // the pin does not accept this sender
  kRejectNoIdentity,   // session 0
};
const char* SourceDecisionName(SourceDecision d);
inline bool IsRejection(SourceDecision d) {
  return d != SourceDecision::kAccept && d != SourceDecision::kLocked;
}

struct SourceRejectionCounts {
  int64_t other_sender = 0;
  int64_t not_pinned = 0;
  int64_t no_identity = 0;
  int64_t total() const { return other_sender + not_pinned + no_identity; }
};

struct SourceEvent {
  SourceDecision decision = SourceDecision::kAccept;
  bool new_sender = false;  // first pose ever seen from this sender (log it)
};

class PoseSourceLock {
 public:
  // Senders remembered for new_sender / senders_seen; more are still handled
  // correctly, only no longer reported as new.
  static constexpr size_t kSendersRemembered = 64;

  // release_after_ns > 0: silence of the locked stream after which another
  // sender may take over.
  explicit PoseSourceLock(int64_t release_after_ns, PoseSourcePin pin = {});

  // One pose from `sender`, received at now_ns (any monotonic clock);
  // `valid`: it passed pose validation. Only a valid pose locks a sender or
  // keeps its stream alive; an invalid one from the locked sender (or while
  // none is locked) is still passed on, for the validator to count.
  SourceEvent Observe(const SenderId& sender, bool valid, int64_t now_ns);

  bool locked() const { return locks_ > 0; }
  const SenderId& source() const { return source_; }  // meaningful if locked()
  bool alive(int64_t now_ns) const { return locked() && now_ns - last_valid_ns_ < release_after_ns_; }
  int64_t last_valid_ns() const { return last_valid_ns_; }
  int64_t locks() const { return locks_; }
  const PoseSourcePin& pin() const { return pin_; }
  const SourceRejectionCounts& rejections() const { return rejections_; }
  int64_t senders_seen() const { return static_cast<int64_t>(seen_count_); }

 private:
  bool Remember(const SenderId& s);  // true if s was not seen before

  int64_t release_after_ns_;
  PoseSourcePin pin_;
  SenderId source_;
  int64_t last_valid_ns_ = 0;
  int64_t locks_ = 0;
  SourceRejectionCounts rejections_;
  std::array<SenderId, kSendersRemembered> seen_{};
  size_t seen_count_ = 0;
};

}  // namespace haptics
