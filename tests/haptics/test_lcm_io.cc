// The LCM transport over memq:// (in-process; no network).
#include "haptics/io/lcm_io.h"

#include <gtest/gtest.h>

#include <vector>

namespace haptics {
namespace {

haptics_msgs::probe_pose_t Pose(int64_t seq) {
  haptics_msgs::probe_pose_t m{};
  m.version = haptics_msgs::probe_pose_t::VERSION;
  m.sender_session = 0x5e55;
  m.sender_device = "sigma7";
  m.utime = 1000 * seq;
  m.seq = seq;
  m.position[0] = 0.01;
  m.position[1] = -0.02;
  m.position[2] = 0.03;
  m.orientation[0] = 1.0;
  m.has_velocity = true;
  m.linear_velocity[2] = -0.1;
  m.angular_velocity[0] = 0.5;
  return m;
}

std::vector<uint8_t> Encode(const haptics_msgs::probe_pose_t& m) {
  std::vector<uint8_t> bytes(m.getEncodedSize());
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

void HandleAll(lcm::LCM* lcm) {
  while (lcm->handleTimeout(0) > 0) {
  }
}

TEST(PoseReceiver, DecodesPosesAndHandsOverTheNewest) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  LatestValue<PoseSample> poses;
  PoseReceiver receiver(&lcm, "PROBE_POSE", &poses);
  const haptics_msgs::probe_pose_t m = Pose(7);
  lcm.publish("PROBE_POSE", &m);
  lcm.publish("OTHER_CHANNEL", &m);  // ignored
  HandleAll(&lcm);
  const PoseSample* p = poses.TakeNewest();
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->seq, 7);
  EXPECT_EQ(p->utime, 7000);
  EXPECT_EQ(p->session, 0x5e55);
  EXPECT_EQ(p->p_WD, Vector3(0.01, -0.02, 0.03));
  EXPECT_EQ(p->q_WD.w(), 1.0);
  EXPECT_TRUE(p->has_velocity);
  EXPECT_EQ(p->v_WD, Vector3(0, 0, -0.1));
  EXPECT_EQ(p->w_WD, Vector3(0.5, 0, 0));
  EXPECT_GT(p->receive_time_ns, 0);
  EXPECT_EQ(receiver.counts().received, 1);
  EXPECT_EQ(poses.TakeNewest(), nullptr);

  // Three before the loop looks: the newest wins, two are dropped.
  for (int64_t seq : {8, 9, 10}) {
    const haptics_msgs::probe_pose_t mi = Pose(seq);
    lcm.publish("PROBE_POSE", &mi);
  }
  HandleAll(&lcm);
  p = poses.TakeNewest();
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->seq, 10);
  EXPECT_EQ(receiver.counts().received, 4);
  EXPECT_EQ(receiver.counts().dropped, 2);
}

TEST(PoseReceiver, CountsMalformedMessagesWithoutCrashing) {
  lcm::LCM lcm("memq://");
  LatestValue<PoseSample> poses;
  PoseReceiver receiver(&lcm, "PROBE_POSE", &poses);
  const std::vector<uint8_t> good = Encode(Pose(1));
  const std::vector<uint8_t> garbage = {0xde, 0xad, 0xbe, 0xef, 1, 2, 3};
  std::vector<uint8_t> truncated(good.begin(), good.end() - 5);
  std::vector<uint8_t> trailing = good;
  trailing.push_back(0);
  haptics_msgs::wrench_t wrong_type{};
  lcm.publish("PROBE_POSE", garbage.data(), garbage.size());
  lcm.publish("PROBE_POSE", truncated.data(), truncated.size());
  lcm.publish("PROBE_POSE", trailing.data(), trailing.size());
  lcm.publish("PROBE_POSE", &wrong_type);
  lcm.publish("PROBE_POSE", good.data(), 0);
  HandleAll(&lcm);
  EXPECT_EQ(receiver.counts().malformed, 5);
  EXPECT_EQ(receiver.counts().received, 0);
  EXPECT_EQ(poses.TakeNewest(), nullptr);
  lcm.publish("PROBE_POSE", good.data(), good.size());
  HandleAll(&lcm);
  EXPECT_EQ(receiver.counts().received, 1);
  EXPECT_NE(poses.TakeNewest(), nullptr);
}

// A function-pointer handler: LCM's member-function subscribe form trips a
// GCC UBSan false positive ("member access within null pointer" on the ->*
// call in lcm-cpp-impl.hpp), and the server uses this form anyway.
using Wrenches = std::vector<haptics_msgs::wrench_t>;
void CollectWrench(const lcm::ReceiveBuffer*, const std::string&, const haptics_msgs::wrench_t* m,
                   Wrenches* got) {
  got->push_back(*m);
}

TEST(LcmWrenchPublisher, PublishesEveryFieldAndTheFlags) {
  lcm::LCM lcm("memq://");
  Wrenches got;
  lcm.subscribeFunction("HAPTIC_WRENCH", &CollectWrench, &got);
  LcmWrenchPublisher publisher(&lcm, "HAPTIC_WRENCH");
  WrenchOutput out;
  out.tick = 42;
  out.pose_seq = 41;
  out.pose_utime = 123456;
  out.pose_session = 0x5e55;
  out.wrench.f_W = Vector3(1, -2, 3);
  out.wrench.tau_W = Vector3(0.01, 0.02, -0.03);
  out.penetration_depth = 0.002;
  out.contact_count = 3;
  out.solver_time_us = 55.5;
  out.flags = kFlagForceSaturated | kFlagPdInvalid;
  const int64_t before = MonotonicMicros();
  publisher.Publish(out);
  HandleAll(&lcm);
  ASSERT_EQ(got.size(), 1u);
  const haptics_msgs::wrench_t& m = got[0];
  EXPECT_EQ(m.seq, 42);
  EXPECT_EQ(m.pose_seq, 41);
  EXPECT_EQ(m.pose_utime, 123456);
  EXPECT_EQ(m.pose_session, 0x5e55);
  EXPECT_GE(m.utime, before);
  EXPECT_EQ(m.force[1], -2.0);
  EXPECT_EQ(m.torque[2], -0.03);
  EXPECT_EQ(m.penetration_depth, 0.002);
  EXPECT_EQ(m.contact_count, 3);
  EXPECT_EQ(m.solver_time_us, 55.5);
  EXPECT_EQ(m.flags, haptics_msgs::wrench_t::FLAG_FORCE_SATURATED |
                         haptics_msgs::wrench_t::FLAG_PD_INVALID);
  EXPECT_EQ(publisher.publish_errors(), 0);
}

TEST(StatusMessage, CarriesLoopAndReceiverCounters) {
  LoopStatus loop;
  loop.tick_count = 1000;
  loop.target_rate_hz = 1000.0;
  loop.achieved_rate_hz = 999.5;
  loop.jitter_us = {100, 3.0, 20.0, 40.0};
  loop.compute_us = {100, 50.0, 90.0, 120.0};
  loop.deadline_misses = 9;
  loop.misses_compute = 2;
  loop.misses_stalled = 3;
  loop.misses_charged = 4;
  loop.misses_late_wakeup = 4;
  loop.realtime = true;
  loop.renderer.poses_rejected.bad_quaternion = 3;
  loop.renderer.poses_rejected.outside_workspace = 1;
  loop.renderer.limiter.saturated = 9;
  loop.renderer.watchdog_trips = 1;
  const haptics_msgs::server_status_t m = MakeStatusMessage(loop, {990, 4, 6});
  EXPECT_EQ(m.tick_count, 1000);
  EXPECT_EQ(m.achieved_rate_hz, 999.5);
  EXPECT_EQ(m.period_jitter_p99_us, 20.0);
  EXPECT_EQ(m.compute_max_us, 120.0);
  EXPECT_EQ(m.deadline_misses, 9);
  EXPECT_EQ(m.misses_compute, 2);
  EXPECT_EQ(m.misses_stalled, 3);
  EXPECT_EQ(m.misses_charged, 4);
  EXPECT_EQ(m.misses_late_wakeup, 4);
  EXPECT_EQ(m.poses_received, 990);
  EXPECT_EQ(m.messages_malformed, 4);
  EXPECT_EQ(m.poses_dropped, 6);
  EXPECT_EQ(m.poses_rejected, 4);
  EXPECT_EQ(m.force_saturations, 9);
  EXPECT_EQ(m.watchdog_trips, 1);
  EXPECT_EQ(m.realtime, 1);
}

}  // namespace
}  // namespace haptics
