#pragma once
// Receives the server's wrench and status messages for probe_replay on the
// LCM handler thread: matches each wrench to the pose it answers, keeps the
// latest status and notes that the server is up. While the replay is
// sending, a status that names this replay's session as the last rejected
// sender, or another sender as the pose source, is counted: the server is
// not rendering us (probe_replay fails the run). Subscribes with
// subscribeFunction and decodes itself: LCM 1.3.1's member-function
// subscriptions crash in sanitizer builds (PD_SANITIZE).
#include <atomic>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <optional>
#include <string>

#include "haptics_msgs/server_status_t.hpp"
#include "haptics_msgs/wrench_t.hpp"
#include "msgs/sender_identity.h"
#include "probes/transport/mono_clock.h"
#include "probes/results/seq_matcher.h"

namespace probes {

class ReplayListener {
 public:
  explicit ReplayListener(SeqMatcher* matcher) : matcher_(matcher) {}

  void Subscribe(lcm::LCM* lcm, const std::string& wrench_channel,
                 const std::string& status_channel) {
    lcm->subscribeFunction(wrench_channel, &ReplayListener::OnWrench, this);
    lcm->subscribeFunction(status_channel, &ReplayListener::OnStatus, this);
  }

  // What the LCM callbacks do, callable without LCM (unit tests).
  void HandleWrench(const haptics_msgs::wrench_t& msg, int64_t receive_us) {
    WrenchAnswer a;
    a.pose_seq = msg.pose_seq;
    a.pose_utime = msg.pose_utime;
    a.pose_session = msg.pose_session;
    for (int i = 0; i < 3; ++i) {
      a.force[i] = msg.force[i];
      a.torque[i] = msg.torque[i];
    }
    a.penetration_depth = msg.penetration_depth;
    a.contact_count = msg.contact_count;
    a.flags = msg.flags;
    server_seen_ = true;
    std::lock_guard<std::mutex> lock(mutex_);
    // The server numbers its ticks: a jump in wrench seq is wrenches lost in
    // transport (e.g. a full socket buffer), whose poses may look unanswered.
    if (last_wrench_seq_ >= 0 && msg.seq > last_wrench_seq_ + 1)
      wrenches_missed_ += msg.seq - last_wrench_seq_ - 1;
    if (msg.seq > last_wrench_seq_) last_wrench_seq_ = msg.seq;
    if (matcher_->Match(a, receive_us) == SeqMatcher::Outcome::kFirstAnswer) ++first_answers_;
  }

  // How long after our first pose a status may still show the previous
  // source (it may have been put together just before our pose arrived).
  static constexpr int64_t kStatusSettleUs = 20'000;

  void HandleStatus(const haptics_msgs::server_status_t& msg, int64_t receive_us = MonotonicUs()) {
    server_seen_ = true;
    std::lock_guard<std::mutex> lock(mutex_);
    last_status_ = msg;
    if (!matcher_->Sending(receive_us, kStatusSettleUs)) return;
    if (msg.last_rejected_session == matcher_->session()) ++statuses_rejecting_us_;
    if (msg.source_session != matcher_->session()) {
      if (statuses_other_source_++ == 0) {
        other_source_session_ = msg.source_session;
        other_source_device_ = msg.source_device;
      }
    }
  }

  // Guards the matcher: the sender thread marks poses sent under it.
  std::mutex& mutex() { return mutex_; }
  bool server_seen() const { return server_seen_.load(); }
  int64_t first_answers() const { return first_answers_.load(); }
  // Wrenches the server published (by its tick seq) that never arrived here.
  int64_t wrenches_missed() {
    std::lock_guard<std::mutex> lock(mutex_);
    return wrenches_missed_;
  }
  // Statuses received while sending that say our poses were rejected, or
  // that another sender (first one: other_source_*) is the pose source.
  int64_t statuses_rejecting_us() {
    std::lock_guard<std::mutex> lock(mutex_);
    return statuses_rejecting_us_;
  }
  int64_t statuses_other_source() {
    std::lock_guard<std::mutex> lock(mutex_);
    return statuses_other_source_;
  }
  std::string other_source() {
    std::lock_guard<std::mutex> lock(mutex_);
    return haptics_msgs::FormatSession(other_source_session_) + " '" + other_source_device_ + "'";
  }
  std::optional<haptics_msgs::server_status_t> last_status() {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_status_;
  }

 private:
  // Undecodable messages (wrong type, truncated) are ignored.
  static void OnWrench(const lcm::ReceiveBuffer* rbuf, const std::string&, ReplayListener* self) {
    // Timestamp first so that decoding and lock contention are not counted as latency.
    const int64_t receive_us = MonotonicUs();
    haptics_msgs::wrench_t msg{};
    if (msg.decode(rbuf->data, 0, rbuf->data_size) != static_cast<int>(rbuf->data_size)) return;
    self->HandleWrench(msg, receive_us);
  }

  static void OnStatus(const lcm::ReceiveBuffer* rbuf, const std::string&, ReplayListener* self) {
    haptics_msgs::server_status_t msg{};
    if (msg.decode(rbuf->data, 0, rbuf->data_size) != static_cast<int>(rbuf->data_size)) return;
    self->HandleStatus(msg);
  }

  SeqMatcher* matcher_;
  std::mutex mutex_;
  int64_t last_wrench_seq_ = -1;
  int64_t wrenches_missed_ = 0;
  int64_t statuses_rejecting_us_ = 0, statuses_other_source_ = 0;
  int64_t other_source_session_ = 0;
  std::string other_source_device_;
  std::atomic<bool> server_seen_{false};
  std::atomic<int64_t> first_answers_{0};
  std::optional<haptics_msgs::server_status_t> last_status_;
};

}  // namespace probes
