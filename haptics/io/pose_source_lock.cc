#include "haptics/io/pose_source_lock.h"

#include <algorithm>

namespace haptics {

SenderId SenderId::Make(int64_t session, std::string_view device) {
  SenderId s;
  s.session = session;
  const size_t n = std::min(device.size(), kMaxDeviceNameBytes);
  std::copy_n(device.data(), n, s.device.data());
  s.device[n] = '\0';
  return s;
}

const char* SourceDecisionName(SourceDecision d) {
  switch (d) {
    case SourceDecision::kAccept: return "accepted";
    case SourceDecision::kLocked: return "locked";
    case SourceDecision::kRejectOtherSender: return "another sender holds the lock";
    case SourceDecision::kRejectNotPinned: return "not the pinned sender";
    case SourceDecision::kRejectNoIdentity: return "no sender identity";
  }
  return "unknown";
}

PoseSourceLock::PoseSourceLock(int64_t release_after_ns, PoseSourcePin pin)
    : release_after_ns_(release_after_ns), pin_(std::move(pin)) {}

bool PoseSourceLock::Remember(const SenderId& s) {
  for (size_t i = 0; i < seen_count_; ++i) {
    if (seen_[i] == s) return false;
  }
  if (seen_count_ == seen_.size()) return false;  // table full: no longer reported
  seen_[seen_count_++] = s;
  return true;
}

SourceEvent PoseSourceLock::Observe(const SenderId& sender, bool valid, int64_t now_ns) {
  SourceEvent e;
  // The locked sender's poses take the short path (no table search).
  if (locked() && sender == source_) {
    if (valid) last_valid_ns_ = now_ns;
    return e;
  }
  e.new_sender = Remember(sender);
  if (sender.session == 0) {
    ++rejections_.no_identity;
    e.decision = SourceDecision::kRejectNoIdentity;
  } else if (!pin_.Accepts(sender)) {
    ++rejections_.not_pinned;
    e.decision = SourceDecision::kRejectNotPinned;
  } else if (alive(now_ns)) {
    ++rejections_.other_sender;
    e.decision = SourceDecision::kRejectOtherSender;
  } else if (valid) {
    // No stream yet, or the locked one fell silent long enough: take over.
    source_ = sender;
    last_valid_ns_ = now_ns;
    ++locks_;
    e.decision = SourceDecision::kLocked;
  }
  // else: invalid pose and nobody alive: passed on (kAccept) for the
  // validator to reject and count; it locks nothing.
  return e;
}

}  // namespace haptics
