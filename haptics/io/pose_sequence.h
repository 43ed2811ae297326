#pragma once
// Watches the order of incoming probe poses by their `seq` and sender `utime`
// (probe_pose_t) and classifies each one, so that the server can count
// anomalies in its status: a seq that does not increase (duplicate or
// backwards: reordered or replayed), seq numbers jumped over (lost on the
// way), and a utime below the previous one (the sender's clock went back).
// Counting only: the servo loop still renders the newest pose received, and
// the velocity estimator ignores time steps it cannot trust. Single thread.
#include <cstdint>

namespace haptics {

struct PoseSequenceEvent {
  bool out_of_order = false;   // seq <= previous seq
  int64_t skipped = 0;         // seq numbers missing between previous and this one
  bool time_backwards = false; // utime < previous utime (us)
};

class PoseSequenceMonitor {
 public:
  // The first pose is never an anomaly; each later one is compared with the
  // one before it, so a sender that restarts from seq 0 counts once and is
  // then followed normally (one stray pose counts twice: going and coming).
  PoseSequenceEvent Observe(int64_t seq, int64_t utime);

 private:
  bool has_previous_ = false;
  int64_t previous_seq_ = 0;
  int64_t previous_utime_ = 0;
};

}  // namespace haptics
