#include "haptics/io/pose_sequence.h"

#include <limits>

namespace haptics {

PoseSequenceEvent PoseSequenceMonitor::Observe(int64_t seq, int64_t utime) {
  PoseSequenceEvent e;
  if (has_previous_) {
    if (seq <= previous_seq_) {
      e.out_of_order = true;
    } else {
      // seq - previous - 1 in unsigned arithmetic (no overflow), saturated.
      const uint64_t gap = static_cast<uint64_t>(seq) - static_cast<uint64_t>(previous_seq_) - 1;
      constexpr uint64_t kMax = static_cast<uint64_t>(std::numeric_limits<int64_t>::max());
      e.skipped = static_cast<int64_t>(gap > kMax ? kMax : gap);
    }
    e.time_backwards = utime < previous_utime_;
  }
  previous_seq_ = seq;
  previous_utime_ = utime;
  has_previous_ = true;
  return e;
}

}  // namespace haptics
