#pragma once
// LCM transport of the server (not in haptics_core, which stays LCM-free):
//  - PoseReceiver: a thread running lcm.handleTimeout() that decodes
//    probe_pose_t itself from the raw buffer (so undecodable messages are
//    counted, never fatal) and hands the newest pose to the servo loop
//    through a LatestValue (lock-free triple buffer);
//  - LcmWrenchPublisher: encodes wrench_t into a preallocated buffer and
//    publishes the bytes from the loop thread (the templated LCM::publish
//    allocates per call; the raw one does not, and for a short message udpm
//    is one sendmsg under the instance's transmit lock);
//  - MakeStatusMessage: server_status_t from the loop's status and counters.
#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "haptics/arrival_signal.h"
#include "haptics/latest_value.h"
#include "haptics/pose_sample.h"
#include "haptics/pose_sequence.h"
#include "haptics/servo_loop.h"
#include "haptics/wrench_output.h"
#include "haptics_msgs/probe_pose_t.hpp"
#include "haptics_msgs/server_status_t.hpp"
#include "haptics_msgs/wrench_t.hpp"

namespace haptics {

// CLOCK_MONOTONIC in microseconds, the time base of utime fields.
int64_t MonotonicMicros();

// A decoded probe pose as a PoseSample (receive_time_ns left for the caller).
PoseSample ToPoseSample(const haptics_msgs::probe_pose_t& msg);

struct ReceiverCounts {
  int64_t received = 0;   // decoded poses handed to the loop
  int64_t malformed = 0;  // undecodable messages on the pose channel
  int64_t dropped = 0;    // poses superseded before the loop took them
  // Order of the decoded poses (pose_sequence.h); counted, still rendered.
  int64_t out_of_order = 0;    // seq not above the previous pose's
  int64_t seq_skipped = 0;     // seq numbers jumped over (saturating)
  int64_t time_backwards = 0;  // utime below the previous pose's
};

class PoseReceiver {
 public:
  // Subscribes to `channel` on *lcm. Both pointees must outlive this.
  PoseReceiver(lcm::LCM* lcm, std::string channel, LatestValue<PoseSample>* out);
  ~PoseReceiver();
  PoseReceiver(const PoseReceiver&) = delete;
  PoseReceiver& operator=(const PoseReceiver&) = delete;

  // Runs handleTimeout() on its own thread until StopThread(). Without it,
  // whoever calls lcm->handle() drives the receiver (tests with memq://).
  void StartThread();
  void StopThread();

  // One raw message as it came off the wire.
  void OnMessage(const void* data, int size);

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
  PoseSequenceMonitor sequence_;  // receive thread only
  std::atomic<int64_t> received_{0}, malformed_{0}, dropped_{0};
  std::atomic<int64_t> out_of_order_{0}, seq_skipped_{0}, time_backwards_{0};
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
