#include "probes/results/seq_matcher.h"

#include "haptics_msgs/wrench_t.hpp"

#include <stdexcept>
#include <string>

namespace probes {

SeqMatcher::SeqMatcher(int64_t first_seq, size_t count, int64_t session)
    : first_seq_(first_seq), session_(session), records_(count) {
  for (size_t i = 0; i < count; ++i) records_[i].seq = first_seq + static_cast<int64_t>(i);
}

void SeqMatcher::MarkSent(int64_t seq, int64_t send_us) {
  const int64_t i = seq - first_seq_;
  if (i < 0 || i >= static_cast<int64_t>(records_.size())) {
    throw std::out_of_range("SeqMatcher::MarkSent: seq " + std::to_string(seq) +
                            " outside the planned range");
  }
  if (records_[i].send_us < 0) ++sent_;
  records_[i].send_us = send_us;
  if (first_send_us_ < 0) first_send_us_ = send_us;
  last_send_us_ = send_us;
}

bool SeqMatcher::Sending(int64_t now_us, int64_t settle_us) const {
  if (first_send_us_ < 0 || now_us < first_send_us_ + settle_us) return false;
  return sent_ < records_.size() || now_us <= last_send_us_ + kSendingTailUs;
}

SeqMatcher::Outcome SeqMatcher::Match(const WrenchAnswer& answer, int64_t receive_us) {
  if (answer.pose_seq == -1) {
    ++no_pose_answers_;
    return Outcome::kNoPose;
  }
  if (answer.pose_session != session_) {
    if (answer.pose_session != 0 && (answer.flags & haptics_msgs::wrench_t::FLAG_WATCHDOG) == 0 && Sending(receive_us)) {
      if (other_stream_answers_++ == 0) other_stream_session_ = answer.pose_session;
      return Outcome::kOtherStream;
    }
    ++foreign_answers_;
    return Outcome::kForeign;
  }
  const int64_t i = answer.pose_seq - first_seq_;
  if (i < 0 || i >= static_cast<int64_t>(records_.size()) || records_[i].send_us < 0 ||
      records_[i].send_us != answer.pose_utime) {
    ++foreign_answers_;
    return Outcome::kForeign;
  }
  PoseRecord& r = records_[i];
  if (r.answers++ > 0) {
    ++repeat_answers_;
    return Outcome::kRepeatAnswer;
  }
  r.latency_us = receive_us - r.send_us;
  r.first = answer;
  return Outcome::kFirstAnswer;
}

}  // namespace probes
