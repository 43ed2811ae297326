#pragma once
// Matches wrench answers to the poses the replay sent, by pose_seq. An answer
// counts only if its echoed pose_utime equals the utime the pose was sent
// with, so answers to another sender's poses (or to a previous run that
// reused the same seq numbers) are never mistaken for ours. The first answer
// to a pose gives its latency and wrench; later ones (a server re-answering
// a stale pose) are only counted. Answers must also carry our sender
// session (wrench_t.pose_session); a wrench that renders another sender's
// live stream while we are sending means the server is not rendering us
// (kOtherStream: probe_replay fails the run). Not thread-safe: the caller locks.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace probes {

// What a wrench_t says about the pose it answers.
struct WrenchAnswer {
  int64_t pose_seq = -1;
  int64_t pose_utime = 0;
  int64_t pose_session = 0;            // sender session of the pose it answers (0: none)
  double force[3] = {0.0, 0.0, 0.0};   // f_W (N)
  double torque[3] = {0.0, 0.0, 0.0};  // tau_W (N·m)
  double penetration_depth = 0.0;      // m
  int32_t contact_count = 0;
  int32_t flags = 0;
};

struct PoseRecord {
  int64_t seq = 0;
  int64_t send_us = -1;     // replay CLOCK_MONOTONIC send time; -1 until sent
  int answers = 0;          // how many wrenches answered this pose
  int64_t latency_us = -1;  // first answer's receive time minus send time
  WrenchAnswer first;       // the first answer
  bool answered() const { return answers > 0; }
};

class SeqMatcher {
 public:
  enum class Outcome {
    kFirstAnswer,   // first answer to one of our poses
    kRepeatAnswer,  // a further answer to an already answered pose
    kNoPose,        // pose_seq == -1: the server has not received a pose yet
    kForeign,       // seq not ours, not sent yet, or pose_utime does not match
    kOtherStream,   // renders another sender's live stream while we are sending
  };

  // How long after our last pose another stream's answers are still held
  // against us (us): less than any watchdog timeout, during which the
  // server keeps our stream locked.
  static constexpr int64_t kSendingTailUs = 20'000;

  // Poses first_seq .. first_seq + count - 1 will be sent by `session`.
  SeqMatcher(int64_t first_seq, size_t count, int64_t session = 0);

  // Records the send time (also the utime put in the pose). Throws
  // std::out_of_range for a seq outside the range given at construction.
  void MarkSent(int64_t seq, int64_t send_us);

  Outcome Match(const WrenchAnswer& answer, int64_t receive_us);

  // True from our first send until kSendingTailUs after the last one
  // (receive clock = send clock, CLOCK_MONOTONIC us), plus settle_us at the start.
  bool Sending(int64_t now_us, int64_t settle_us = 0) const;

  const std::vector<PoseRecord>& records() const { return records_; }
  int64_t session() const { return session_; }
  int64_t other_stream_answers() const { return other_stream_answers_; }
  int64_t other_stream_session() const { return other_stream_session_; }  // the first one seen
  int64_t first_seq() const { return first_seq_; }
  int64_t repeat_answers() const { return repeat_answers_; }
  int64_t no_pose_answers() const { return no_pose_answers_; }
  int64_t foreign_answers() const { return foreign_answers_; }

 private:
  int64_t first_seq_;
  int64_t session_;
  std::vector<PoseRecord> records_;
  size_t sent_ = 0;
  int64_t first_send_us_ = -1, last_send_us_ = -1;
  int64_t other_stream_answers_ = 0;
  int64_t other_stream_session_ = 0;
  int64_t repeat_answers_ = 0;
  int64_t no_pose_answers_ = 0;
  int64_t foreign_answers_ = 0;
};

}  // namespace probes
