// The pose receiver's source lock over memq:// (no network): only the locked
// sender's poses reach the loop, others are counted by cause, a changed id
// is a new sender, version-1 traffic is recognised, and the status carries
// the source.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "haptics/io/lcm_io.h"
#include "haptics/scene/load_scene_config.h"
#include "haptics_msgs/probe_pose_v1_t.hpp"

namespace haptics {
namespace {

constexpr int64_t kMs = 1'000'000;  // ns

std::vector<uint8_t> PoseBytes(int64_t session, const std::string& device, int64_t seq,
                               double x = 0.0, int16_t version = haptics_msgs::probe_pose_t::VERSION) {
  haptics_msgs::probe_pose_t m{};
  m.version = version;
  m.sender_session = session;
  m.sender_device = device;
  m.seq = seq;
  m.utime = 1000 * seq;
  m.position[0] = x;
  m.orientation[0] = 1.0;
  std::vector<uint8_t> bytes(m.getEncodedSize());
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

struct Rx {
  lcm::LCM lcm{"memq://"};
  LatestValue<PoseSample> poses;
  PoseReceiver receiver;
  explicit Rx(PoseSourceOptions options = {}) : receiver(&lcm, "PROBE_POSE", &poses, std::move(options)) {}
  // One message at time t_ns; the session of the pose the loop would take (0: none).
  int64_t Send(const std::vector<uint8_t>& bytes, int64_t t_ns) {
    receiver.OnMessage(bytes.data(), static_cast<int>(bytes.size()), t_ns);
    const PoseSample* p = poses.TakeNewest();
    return p != nullptr ? p->session : 0;
  }
};

TEST(PoseSourceReceiver, TwoInterleavedSendersOnlyTheFirstReachesTheLoop) {
  Rx rx;
  for (int64_t k = 1; k <= 1000; ++k) {
    EXPECT_EQ(rx.Send(PoseBytes(0xa, "probe_replay", k, 0.0), k * kMs), 0xa);
    EXPECT_EQ(rx.Send(PoseBytes(0xb, "probe_sim", 5000 + k, 0.06), k * kMs + kMs / 2), 0);
  }
  const ReceiverCounts c = rx.receiver.counts();
  EXPECT_EQ(c.received, 1000);
  EXPECT_EQ(c.source_rejected.other_sender, 1000);
  EXPECT_EQ(c.rejected_total(), 1000);
  // The rejected stream's seq never mixes into the locked one's order counts.
  EXPECT_EQ(c.out_of_order, 0);
  EXPECT_EQ(c.seq_skipped, 0);
  EXPECT_EQ(c.source.source.session, 0xa);
  EXPECT_EQ(c.source.source.device_name(), "probe_replay");
  EXPECT_EQ(c.source.locks, 1);
  EXPECT_EQ(c.source.senders_seen, 2);
  EXPECT_EQ(c.source.last_rejected_session, 0xb);

  const haptics_msgs::server_status_t m = MakeStatusMessage(LoopStatus{}, c);
  EXPECT_EQ(m.source_session, 0xa);
  EXPECT_EQ(m.source_device, "probe_replay");
  EXPECT_EQ(m.source_locks, 1);
  EXPECT_FALSE(m.source_pinned);
  EXPECT_EQ(m.poses_rejected_other_sender, 1000);
  EXPECT_EQ(m.last_rejected_session, 0xb);
  EXPECT_EQ(m.senders_seen, 2);
}

TEST(PoseSourceReceiver, TakeoverAfterTheReleaseTimeRestartsTheSequence) {
  PoseSourceOptions options;
  options.release_after_s = 0.1;
  Rx rx(options);
  for (int64_t k = 1; k <= 100; ++k) rx.Send(PoseBytes(0xa, "first", k), k * kMs);
  // A stops at 100 ms. B (its own seq from 1) is rejected until 200 ms.
  EXPECT_EQ(rx.Send(PoseBytes(0xb, "second", 1), 199 * kMs), 0);
  EXPECT_EQ(rx.Send(PoseBytes(0xb, "second", 2), 200 * kMs), 0xb);
  EXPECT_EQ(rx.Send(PoseBytes(0xb, "second", 3), 201 * kMs), 0xb);
  EXPECT_EQ(rx.Send(PoseBytes(0xa, "first", 101), 202 * kMs), 0);  // A is now the stranger
  const ReceiverCounts c = rx.receiver.counts();
  EXPECT_EQ(c.source.source.session, 0xb);
  EXPECT_EQ(c.source.locks, 2);
  EXPECT_EQ(c.source_rejected.other_sender, 2);
  EXPECT_EQ(c.out_of_order, 0) << "B's seq 2 after A's seq 100 is a new stream, not a reorder";
}

TEST(PoseSourceReceiver, ASenderThatChangesItsIdMidStreamIsANewSender) {
  Rx rx;
  for (int64_t k = 1; k <= 50; ++k) EXPECT_EQ(rx.Send(PoseBytes(0xa, "sigma7", k), k * kMs), 0xa);
  // Same process, same device, seq continuing, but a new session id.
  for (int64_t k = 51; k <= 100; ++k) EXPECT_EQ(rx.Send(PoseBytes(0xc, "sigma7", k), k * kMs), 0) << k;
  const ReceiverCounts c = rx.receiver.counts();
  EXPECT_EQ(c.source_rejected.other_sender, 50);
  EXPECT_EQ(c.source.source.session, 0xa);
  EXPECT_EQ(c.source.senders_seen, 2);
}

TEST(PoseSourceReceiver, AnInvalidFirstPoseLocksNothing) {
  PoseSourceOptions options;
  options.workspace_min = Vector3::Constant(-0.1);
  options.workspace_max = Vector3::Constant(0.1);
  Rx rx(options);
  // B's pose is outside the workspace: passed on for the validator to count, no lock.
  EXPECT_EQ(rx.Send(PoseBytes(0xb, "broken", 1, 5.0), kMs), 0xb);
  EXPECT_EQ(rx.receiver.counts().source.locks, 0);
  EXPECT_EQ(rx.Send(PoseBytes(0xa, "sigma7", 1, 0.0), 2 * kMs), 0xa);
  EXPECT_EQ(rx.Send(PoseBytes(0xb, "broken", 2, 0.0), 3 * kMs), 0);
  EXPECT_EQ(rx.receiver.counts().source.source.session, 0xa);
}

TEST(PoseSourceReceiver, PinnedDeviceAndEveryRejectionCause) {
  PoseSourceOptions options;
  options.pin.device = "sigma7";
  Rx rx(options);
  EXPECT_EQ(rx.Send(PoseBytes(0xb, "probe_sim", 1), kMs), 0);                 // not pinned
  EXPECT_EQ(rx.Send(PoseBytes(0, "sigma7", 1), 2 * kMs), 0);                  // no identity
  EXPECT_EQ(rx.Send(PoseBytes(0xa, std::string(65, 'x'), 1), 3 * kMs), 0);    // name too long
  EXPECT_EQ(rx.Send(PoseBytes(0xa, "sigma7", 1, 0.0, 3), 4 * kMs), 0);        // version 3
  haptics_msgs::probe_pose_v1_t old{};
  old.seq = 1;
  old.orientation[0] = 1.0;
  std::vector<uint8_t> v1(old.getEncodedSize());
  old.encode(v1.data(), 0, static_cast<int>(v1.size()));
  EXPECT_EQ(rx.Send(v1, 5 * kMs), 0);                                         // version 1
  EXPECT_EQ(rx.Send(PoseBytes(0xa, "sigma7", 2), 6 * kMs), 0xa);              // the pinned device
  const ReceiverCounts c = rx.receiver.counts();
  EXPECT_EQ(c.source_rejected.not_pinned, 1);
  EXPECT_EQ(c.source_rejected.no_identity, 2);
  EXPECT_EQ(c.wrong_version, 2);
  EXPECT_EQ(c.malformed, 0) << "a version-1 pose is recognised, not garbage";
  EXPECT_EQ(c.received, 1);
  EXPECT_TRUE(c.source.pinned);
  const haptics_msgs::server_status_t m = MakeStatusMessage(LoopStatus{}, c);
  EXPECT_TRUE(m.source_pinned);
  EXPECT_EQ(m.poses_rejected_not_pinned, 1);
  EXPECT_EQ(m.poses_rejected_no_identity, 2);
  EXPECT_EQ(m.poses_rejected_version, 2);
}

TEST(PoseSourceReceiver, ASceneReleasesAfterItsWatchdogRampAndChecksItsWorkspace) {
  const SceneConfig config = LoadSceneConfig(HAPTICS_CONFIG_DIR "/box_on_box.yaml");
  const PoseSourceOptions o = MakePoseSourceOptions(config, PoseSourcePin{});
  // watchdog 50 ms + ramp 50 ms + two 1 ms periods (config/box_on_box.yaml).
  EXPECT_NEAR(o.release_after_s, 0.102, 1e-12);
  EXPECT_EQ(o.workspace_min, Vector3(-0.1, -0.1, -0.07));
  EXPECT_EQ(o.workspace_max, Vector3(0.1, 0.1, 0.07));
  EXPECT_FALSE(o.pin.active());
}

}  // namespace
}  // namespace haptics
