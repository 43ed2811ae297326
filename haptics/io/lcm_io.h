#pragma once
// LCM transport of the server (not in haptics_core, which stays LCM-free):
//  - PoseReceiver: a thread running lcm.handleTimeout() that decodes
//    probe_pose_t itself from the raw buffer (so undecodable messages are
//    counted, never fatal), passes only the locked sender's stream
//    (pose_source_lock.h; others are counted and logged once per sender)
//    and hands the newest pose to the servo loop through a LatestValue
//    (lock-free triple buffer);
//  - LcmWrenchPublisher: encodes wrench_t into a preallocated buffer and
//    publishes the bytes from the loop thread (the templated LCM::publish
//    allocates per call; the raw one does not, and for a short message udpm
//    is one sendmsg under the instance's transmit lock);
//  - MakeStatusMessage: server_status_t from the loop's status and counters.
#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <limits>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "haptics/loop/arrival_signal.h"
#include "haptics/loop/latest_value.h"
#include "haptics/scene/scene_config.h"
#include "haptics/io/pose_sample.h"
#include "haptics/io/pose_sequence.h"
#include "haptics/io/pose_source_lock.h"
#include "haptics/io/pose_validation.h"
#include "haptics/loop/servo_loop.h"
#include "haptics/io/wrench_output.h"
#include "haptics_msgs/probe_pose_t.hpp"
#include "haptics_msgs/server_status_t.hpp"
#include "haptics_msgs/wrench_t.hpp"

namespace haptics {

// CLOCK_MONOTONIC in microseconds, the time base of utime fields.
int64_t MonotonicMicros();

// A decoded probe pose as a PoseSample (receive_time_ns left for the caller).
PoseSample ToPoseSample(const haptics_msgs::probe_pose_t& msg);

// The pose source as the status reports it.
struct PoseSourceStatus {
  SenderId source;        // the locked sender (session 0: none yet)
  bool alive = false;     // its stream is within the release time
  bool pinned = false;    // a pin restricts the senders
  int64_t locks = 0;      // streams locked so far (1 + takeovers)
  int64_t last_rejected_session = 0;  // sender of the latest rejected pose (0: none)
  int64_t senders_seen = 0;
};

struct ReceiverCounts {
  int64_t received = 0;   // decoded poses of the locked stream handed to the loop
  int64_t malformed = 0;  // undecodable messages on the pose channel
  int64_t dropped = 0;    // poses superseded before the loop took them
  // Order of the locked stream's poses (pose_sequence.h); counted, still
  // rendered. Restarted when another sender takes over.
  int64_t out_of_order = 0;    // seq not above the previous pose's
  int64_t seq_skipped = 0;     // seq numbers jumped over (saturating)
  int64_t time_backwards = 0;  // utime below the previous pose's
  // Decoded poses not handed to the loop, by cause.
  SourceRejectionCounts source_rejected;  // other sender, not pinned, no identity
  int64_t wrong_version = 0;   // probe_pose_t of another version (version 1: no identity)
  PoseSourceStatus source;
  int64_t rejected_total() const { return source_rejected.total() + wrong_version; }
};

// How the receiver picks the one stream it passes on.
struct PoseSourceOptions {
  // A locked stream silent this long may be taken over (s): the watchdog
  // timeout plus its ramp, so that the force has gone to zero.
  double release_after_s = 0.1;
  PoseSourcePin pin;
  // Only a pose valid by these bounds can lock a sender (PoseValidator::Check).
  Vector3 workspace_min = Vector3::Constant(-std::numeric_limits<double>::infinity());
  Vector3 workspace_max = Vector3::Constant(std::numeric_limits<double>::infinity());
};

// The receiver options of a scene: release after servo.watchdog_timeout_s +
// servo.watchdog_ramp_s + two servo periods, the device workspace, and `pin`.
PoseSourceOptions MakePoseSourceOptions(const SceneConfig& config, PoseSourcePin pin);

class PoseReceiver {
 public:
  // Subscribes to `channel` on *lcm. Both pointees must outlive this.
  PoseReceiver(lcm::LCM* lcm, std::string channel, LatestValue<PoseSample>* out,
               PoseSourceOptions options = {});
  ~PoseReceiver();
  PoseReceiver(const PoseReceiver&) = delete;
  PoseReceiver& operator=(const PoseReceiver&) = delete;

  // Runs handleTimeout() on its own thread until StopThread(). Without it,
  // whoever calls lcm->handle() drives the receiver (tests with memq://).
  void StartThread();
  void StopThread();

  // One raw message as it came off the wire (receive_ns: CLOCK_MONOTONIC,
  // 0 = now).
  void OnMessage(const void* data, int size, int64_t receive_ns = 0);

  // Any thread (the source snapshot is read through a triple buffer whose
  // one reader is the caller: call it from one thread only).
  ReceiverCounts counts() const;
  // Notified after every pose handed over (before StartThread; not owned).
  void set_arrival_signal(ArrivalSignal* arrivals) { arrivals_ = arrivals; }

 private:
  static void Handle(const lcm::ReceiveBuffer* rbuf, const std::string& channel, PoseReceiver* self);

  lcm::LCM* lcm_;
  std::string channel_;
  LatestValue<PoseSample>* out_;
  ArrivalSignal* arrivals_ = nullptr;
  lcm::Subscription* subscription_ = nullptr;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  void Reject(SourceDecision why, int64_t session);  // counts one rejected pose
  void PublishSourceStatus();

  // Receive thread only:
  PoseSequenceMonitor sequence_;
  PoseSourceLock lock_;
  PoseValidator validator_;
  bool logged_version_ = false, logged_table_full_ = false;
  // Shared with counts():
  std::atomic<int64_t> received_{0}, malformed_{0}, dropped_{0};
  std::atomic<int64_t> out_of_order_{0}, seq_skipped_{0}, time_backwards_{0};
  std::atomic<int64_t> other_sender_{0}, not_pinned_{0}, no_identity_{0}, wrong_version_{0};
  std::atomic<int64_t> last_valid_ns_{0}, last_rejected_session_{0};
  int64_t release_after_ns_;
  mutable LatestValue<PoseSourceStatus> source_status_;  // written on lock changes, read by counts()
  mutable PoseSourceStatus source_snapshot_;        // the reader's copy
};

class LcmWrenchPublisher final : public WrenchSink {
 public:
  LcmWrenchPublisher(lcm::LCM* lcm, std::string channel);
  void Publish(const WrenchOutput& output) override;
  int64_t publish_errors() const { return publish_errors_; }

 private:
  lcm::LCM* lcm_;
  std::string channel_;
  haptics_msgs::wrench_t msg_{};
  std::vector<uint8_t> buffer_;
  int64_t publish_errors_ = 0;
};

haptics_msgs::server_status_t MakeStatusMessage(const LoopStatus& loop, const ReceiverCounts& rx);

}  // namespace haptics
