#include "probes/seq_matcher.h"

#include <stdexcept>
#include <string>

namespace probes {

SeqMatcher::SeqMatcher(int64_t first_seq, size_t count) : first_seq_(first_seq), records_(count) {
  for (size_t i = 0; i < count; ++i) records_[i].seq = first_seq + static_cast<int64_t>(i);
}

void SeqMatcher::MarkSent(int64_t seq, int64_t send_us) {
  const int64_t i = seq - first_seq_;
  if (i < 0 || i >= static_cast<int64_t>(records_.size())) {
    throw std::out_of_range("SeqMatcher::MarkSent: seq " + std::to_string(seq) +
                            " outside the planned range");
  }
  records_[i].send_us = send_us;
}

SeqMatcher::Outcome SeqMatcher::Match(const WrenchAnswer& answer, int64_t receive_us) {
  if (answer.pose_seq == -1) {
    ++no_pose_answers_;
    return Outcome::kNoPose;
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
