#include "haptics/io/lcm_io.h"

#include <pthread.h>
#include <time.h>

#include <limits>

#include <spdlog/spdlog.h>

#include "haptics_msgs/probe_pose_v1_t.hpp"

namespace haptics {

using haptics_msgs::wrench_t;
static_assert(kFlagForceSaturated == int32_t{wrench_t::FLAG_FORCE_SATURATED} &&
                  kFlagTorqueSaturated == int32_t{wrench_t::FLAG_TORQUE_SATURATED} &&
                  kFlagRateLimited == int32_t{wrench_t::FLAG_RATE_LIMITED} &&
                  kFlagWatchdog == int32_t{wrench_t::FLAG_WATCHDOG} &&
                  kFlagStaleInput == int32_t{wrench_t::FLAG_STALE_INPUT} &&
                  kFlagSoftEngage == int32_t{wrench_t::FLAG_SOFT_ENGAGE} &&
                  kFlagPdInvalid == int32_t{wrench_t::FLAG_PD_INVALID} &&
                  kFlagContactHeld == int32_t{wrench_t::FLAG_CONTACT_HELD} &&
                  kFlagModelStale == int32_t{wrench_t::FLAG_MODEL_STALE},
              "wrench_output.h flags must match wrench_t.lcm");

namespace {

// How long the receive thread blocks before checking for a stop.
constexpr int kHandleTimeoutMs = 50;

int64_t MonotonicNanos() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace

int64_t MonotonicMicros() { return MonotonicNanos() / 1000; }

PoseSample ToPoseSample(const haptics_msgs::probe_pose_t& msg) {
  PoseSample s;
  s.seq = msg.seq;
  s.utime = msg.utime;
  s.session = msg.sender_session;
  s.p_WD = Vector3(msg.position[0], msg.position[1], msg.position[2]);
  s.q_WD = Quaternion(msg.orientation[0], msg.orientation[1], msg.orientation[2], msg.orientation[3]);
  s.has_velocity = msg.has_velocity;
  s.v_WD = Vector3(msg.linear_velocity[0], msg.linear_velocity[1], msg.linear_velocity[2]);
  s.w_WD = Vector3(msg.angular_velocity[0], msg.angular_velocity[1], msg.angular_velocity[2]);
  return s;
}

PoseSourceOptions MakePoseSourceOptions(const SceneConfig& config, PoseSourcePin pin) {
  PoseSourceOptions o;
  // The loop's watchdog counts from the tick that took the last pose, up to
  // a period after its receipt: two periods more and the ramp is surely over.
  o.release_after_s = config.servo.watchdog_timeout_s + config.servo.watchdog_ramp_s + 2.0 / config.servo.rate_hz;
  o.pin = std::move(pin);
  o.workspace_min = config.device.workspace_min;
  o.workspace_max = config.device.workspace_max;
  return o;
}

PoseReceiver::PoseReceiver(lcm::LCM* lcm, std::string channel, LatestValue<PoseSample>* out,
                           PoseSourceOptions options)
    : lcm_(lcm),
      channel_(std::move(channel)),
      out_(out),
      lock_(static_cast<int64_t>(options.release_after_s * 1e9), options.pin),
      validator_(options.workspace_min, options.workspace_max),
      release_after_ns_(static_cast<int64_t>(options.release_after_s * 1e9)) {
  source_snapshot_.pinned = options.pin.active();
  subscription_ = lcm_->subscribeFunction(channel_, &PoseReceiver::Handle, this);
}

PoseReceiver::~PoseReceiver() {
  StopThread();
  if (subscription_ != nullptr) lcm_->unsubscribe(subscription_);
}

void PoseReceiver::StartThread() {
  stop_ = false;
  thread_ = std::thread([this] {
    pthread_setname_np(pthread_self(), "pose_rx");
    while (!stop_.load(std::memory_order_relaxed)) {
      if (lcm_->handleTimeout(kHandleTimeoutMs) < 0) {
        // A socket error: do not spin on it.
        std::this_thread::sleep_for(std::chrono::milliseconds(kHandleTimeoutMs));
      }
    }
  });
}

void PoseReceiver::StopThread() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void PoseReceiver::Handle(const lcm::ReceiveBuffer* rbuf, const std::string& channel,
                          PoseReceiver* self) {
  // The subscription is a regular expression; take only the exact channel.
  if (channel != self->channel_) return;
  self->OnMessage(rbuf->data, static_cast<int>(rbuf->data_size));
}

void PoseReceiver::OnMessage(const void* data, int size, int64_t receive_ns) {
  if (receive_ns == 0) receive_ns = MonotonicNanos();
  haptics_msgs::probe_pose_t msg;
  // Wrong type (fingerprint), truncated, or with trailing bytes: malformed,
  // unless it is a whole version-1 pose (no sender identity).
  if (data == nullptr || size <= 0 || msg.decode(data, 0, size) != size) {
    haptics_msgs::probe_pose_v1_t v1;
    if (data != nullptr && size > 0 && v1.decode(data, 0, size) == size) {
      wrong_version_.fetch_add(1, std::memory_order_relaxed);
      if (!logged_version_) {
        logged_version_ = true;
        spdlog::warn("pose channel {}: rejecting probe_pose_t version 1 (no sender identity, seq {}): "
                     "the sender must send version {} (msgs/README.md); logged once",
                     channel_, v1.seq, int{haptics_msgs::probe_pose_t::VERSION});
      }
      return;
    }
    malformed_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  if (msg.version != haptics_msgs::probe_pose_t::VERSION) {
    wrong_version_.fetch_add(1, std::memory_order_relaxed);
    if (!logged_version_) {
      logged_version_ = true;
      spdlog::warn("pose channel {}: rejecting probe_pose_t with version {} from sender {} '{}' "
                   "(this server reads version {}); logged once",
                   channel_, msg.version, haptics_msgs::FormatSession(msg.sender_session),
                   msg.sender_device, int{haptics_msgs::probe_pose_t::VERSION});
    }
    return;
  }
  const SenderId sender = SenderId::Make(msg.sender_session, msg.sender_device);
  if (msg.sender_device.size() > kMaxDeviceNameBytes) {
    Reject(SourceDecision::kRejectNoIdentity, msg.sender_session);
    return;
  }
  PoseSample& slot = out_->WriteSlot();
  slot = ToPoseSample(msg);
  slot.receive_time_ns = receive_ns;
  const bool valid = validator_.Check(slot) == PoseRejection::kNone;
  const SourceEvent event = lock_.Observe(sender, valid, receive_ns);
  if (IsRejection(event.decision)) {
    // The slot stays the writer's: the rejected pose is simply overwritten.
    Reject(event.decision, msg.sender_session);
    if (event.new_sender) {
      PublishSourceStatus();
      spdlog::warn("pose source: rejecting sender {} '{}' ({}); rendering {} '{}'",
                   haptics_msgs::FormatSession(sender.session), sender.device_name(),
                   SourceDecisionName(event.decision),
                   lock_.locked() ? haptics_msgs::FormatSession(lock_.source().session) : "nobody",
                   lock_.source().device_name());
    }
    return;
  }
  if (event.decision == SourceDecision::kLocked) {
    sequence_ = PoseSequenceMonitor{};  // a new stream: its seq starts anew
    PublishSourceStatus();
    spdlog::info("pose source: {} sender {} '{}'{}", lock_.locks() == 1 ? "locked onto" : "took over by",
                 haptics_msgs::FormatSession(sender.session), sender.device_name(),
                 lock_.pin().active() ? " (pinned)" : "");
  } else if (event.new_sender) {
    PublishSourceStatus();
  }
  if (lock_.locked() && sender == lock_.source())
    last_valid_ns_.store(lock_.last_valid_ns(), std::memory_order_relaxed);
  if (lock_.senders_seen() == static_cast<int64_t>(PoseSourceLock::kSendersRemembered) &&
      !logged_table_full_) {
    logged_table_full_ = true;
    spdlog::warn("pose source: {} senders seen; further new senders are counted but not logged",
                 lock_.senders_seen());
  }

  const PoseSequenceEvent order = sequence_.Observe(msg.seq, msg.utime);
  if (order.out_of_order) out_of_order_.fetch_add(1, std::memory_order_relaxed);
  if (order.time_backwards) time_backwards_.fetch_add(1, std::memory_order_relaxed);
  if (order.skipped > 0) {
    // One writer (this thread): a saturating add by load and store.
    const int64_t before = seq_skipped_.load(std::memory_order_relaxed);
    const int64_t room = std::numeric_limits<int64_t>::max() - before;
    seq_skipped_.store(order.skipped > room ? std::numeric_limits<int64_t>::max() : before + order.skipped,
                       std::memory_order_relaxed);
  }
  if (out_->Publish()) dropped_.fetch_add(1, std::memory_order_relaxed);
  received_.fetch_add(1, std::memory_order_relaxed);
  if (arrivals_ != nullptr) arrivals_->Notify();  // pose-triggered tick
}

void PoseReceiver::Reject(SourceDecision why, int64_t session) {
  switch (why) {
    case SourceDecision::kRejectOtherSender: other_sender_.fetch_add(1, std::memory_order_relaxed); break;
    case SourceDecision::kRejectNotPinned: not_pinned_.fetch_add(1, std::memory_order_relaxed); break;
    case SourceDecision::kRejectNoIdentity: no_identity_.fetch_add(1, std::memory_order_relaxed); break;
    default: return;
  }
  last_rejected_session_.store(session, std::memory_order_relaxed);
}

void PoseReceiver::PublishSourceStatus() {
  PoseSourceStatus& s = source_status_.WriteSlot();
  s = PoseSourceStatus{};
  if (lock_.locked()) s.source = lock_.source();
  s.pinned = lock_.pin().active();
  s.locks = lock_.locks();
  s.senders_seen = lock_.senders_seen();
  source_status_.Publish();
}

ReceiverCounts PoseReceiver::counts() const {
  ReceiverCounts c;
  c.received = received_.load(std::memory_order_relaxed);
  c.malformed = malformed_.load(std::memory_order_relaxed);
  c.dropped = dropped_.load(std::memory_order_relaxed);
  c.out_of_order = out_of_order_.load(std::memory_order_relaxed);
  c.seq_skipped = seq_skipped_.load(std::memory_order_relaxed);
  c.time_backwards = time_backwards_.load(std::memory_order_relaxed);
  c.source_rejected.other_sender = other_sender_.load(std::memory_order_relaxed);
  c.source_rejected.not_pinned = not_pinned_.load(std::memory_order_relaxed);
  c.source_rejected.no_identity = no_identity_.load(std::memory_order_relaxed);
  c.wrong_version = wrong_version_.load(std::memory_order_relaxed);
  if (const PoseSourceStatus* newest = source_status_.TakeNewest()) source_snapshot_ = *newest;
  c.source = source_snapshot_;
  c.source.alive = c.source.source.session != 0 &&
                   MonotonicNanos() - last_valid_ns_.load(std::memory_order_relaxed) < release_after_ns_;
  c.source.last_rejected_session = last_rejected_session_.load(std::memory_order_relaxed);
  return c;
}

LcmWrenchPublisher::LcmWrenchPublisher(lcm::LCM* lcm, std::string channel)
    : lcm_(lcm), channel_(std::move(channel)) {
  // Fixed-size message: one buffer serves every tick.
  buffer_.resize(msg_.getEncodedSize());
}

void LcmWrenchPublisher::Publish(const WrenchOutput& out) {
  msg_.utime = MonotonicMicros();
  msg_.seq = out.tick;
  msg_.pose_seq = out.pose_seq;
  msg_.pose_utime = out.pose_utime;
  msg_.pose_session = out.pose_session;
  for (int i = 0; i < 3; ++i) {
    msg_.force[i] = out.wrench.f_W[i];
    msg_.torque[i] = out.wrench.tau_W[i];
  }
  msg_.penetration_depth = out.penetration_depth;
  msg_.contact_count = out.contact_count;
  msg_.solver_time_us = out.solver_time_us;
  msg_.flags = out.flags;
  const int size = static_cast<int>(buffer_.size());
  if (msg_.encode(buffer_.data(), 0, size) != size ||
      lcm_->publish(channel_, buffer_.data(), static_cast<unsigned>(size)) != 0) {
    ++publish_errors_;
  }
}

haptics_msgs::server_status_t MakeStatusMessage(const LoopStatus& loop, const ReceiverCounts& rx) {
  haptics_msgs::server_status_t m{};
  m.utime = MonotonicMicros();
  m.tick_count = loop.tick_count;
  m.target_rate_hz = loop.target_rate_hz;
  m.achieved_rate_hz = loop.achieved_rate_hz;
  m.period_jitter_p50_us = loop.jitter_us.p50;
  m.period_jitter_p99_us = loop.jitter_us.p99;
  m.period_jitter_max_us = loop.jitter_us.max;
  m.compute_p50_us = loop.compute_us.p50;
  m.compute_p99_us = loop.compute_us.p99;
  m.compute_max_us = loop.compute_us.max;
  m.deadline_misses = loop.deadline_misses;
  m.poses_received = rx.received;
  m.poses_rejected = loop.renderer.poses_rejected.total();
  m.source_session = rx.source.source.session;
  m.source_device = std::string(rx.source.source.device_name());
  m.source_alive = rx.source.alive;
  m.source_pinned = rx.source.pinned;
  m.source_locks = rx.source.locks;
  m.poses_rejected_other_sender = rx.source_rejected.other_sender;
  m.poses_rejected_not_pinned = rx.source_rejected.not_pinned;
  m.poses_rejected_no_identity = rx.source_rejected.no_identity;
  m.poses_rejected_version = rx.wrong_version;
  m.last_rejected_session = rx.source.last_rejected_session;
  m.senders_seen = rx.source.senders_seen;
  m.poses_dropped = rx.dropped;
  m.messages_malformed = rx.malformed;
  m.poses_out_of_order = rx.out_of_order;
  m.pose_seq_skipped = rx.seq_skipped;
  m.pose_time_backwards = rx.time_backwards;
  m.force_saturations = loop.renderer.limiter.saturated;
  m.watchdog_trips = loop.renderer.watchdog_trips;
  m.realtime = loop.realtime ? 1 : 0;
  m.misses_compute = loop.misses_compute;
  m.misses_stalled = loop.misses_stalled;
  m.misses_charged = loop.misses_charged;
  m.misses_late_wakeup = loop.misses_late_wakeup;
  m.late_wakeups = loop.late_wakeups;
  m.wake_latency_p99_us = loop.wake_latency_us.p99;
  m.pd_update_rate_hz = loop.pd_update_rate_hz;
  m.model_age_p50_ticks = loop.model_age_ticks.p50;
  m.model_age_p99_ticks = loop.model_age_ticks.p99;
  m.model_age_max_ticks = loop.model_age_ticks.max;
  m.pd_invalid = loop.renderer.pd_invalid;
  m.pd_held_ticks = loop.renderer.pd_held_ticks;
  m.model_stale_ticks = loop.renderer.model_stale_ticks;
  m.geometry_async = loop.geometry_async ? 1 : 0;
  return m;
}

}  // namespace haptics
