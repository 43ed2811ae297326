// ReplayListener without LCM: wrenches are matched to sent poses, status
// messages are kept, and either marks the server as seen. (Not over memq://:
// LCM 1.3.1's typed-subscription callback trips UBSan's vptr check in
// sanitizer builds.)
#include <gtest/gtest.h>

#include "haptics_msgs/server_status_t.hpp"
#include "haptics_msgs/wrench_t.hpp"
#include "probes/transport/replay_listener.h"

namespace probes {
namespace {

TEST(ReplayListener, StatusMarksServerSeenAndIsKept) {
  SeqMatcher matcher(0, 1);
  ReplayListener listener(&matcher);
  EXPECT_FALSE(listener.server_seen());
  EXPECT_FALSE(listener.last_status().has_value());
  haptics_msgs::server_status_t status{};
  status.messages_malformed = 3;
  listener.HandleStatus(status);
  EXPECT_TRUE(listener.server_seen());
  ASSERT_TRUE(listener.last_status().has_value());
  EXPECT_EQ(listener.last_status()->messages_malformed, 3);
}

TEST(ReplayListener, GapsInTheServerTickSeqAreCountedAsLostWrenches) {
  SeqMatcher matcher(0, 1);
  ReplayListener listener(&matcher);
  haptics_msgs::wrench_t w{};
  w.pose_seq = -1;
  for (int64_t seq : {10, 11, 14, 15, 13 /* late, out of order */, 20}) {
    w.seq = seq;
    listener.HandleWrench(w, 1000 + seq);
  }
  // 12, 13 missing after 11 (13 arrives late but is still counted once as a
  // gap: an upper bound is what the e2e accounting needs) and 16..19.
  EXPECT_EQ(listener.wrenches_missed(), 2 + 4);
}

TEST(ReplayListener, WrenchIsMatchedToItsPose) {
  SeqMatcher matcher(0, 2);
  ReplayListener listener(&matcher);
  matcher.MarkSent(1, 5000);
  haptics_msgs::wrench_t w{};
  w.pose_seq = 1;
  w.pose_utime = 5000;
  w.force[2] = 4.0;
  w.torque[0] = 0.01;
  w.penetration_depth = 0.002;
  w.contact_count = 2;
  w.flags = 32;
  listener.HandleWrench(w, 5250);
  EXPECT_TRUE(listener.server_seen());
  EXPECT_EQ(listener.first_answers(), 1);
  const PoseRecord& r = matcher.records()[1];
  ASSERT_TRUE(r.answered());
  EXPECT_EQ(r.latency_us, 250);
  EXPECT_DOUBLE_EQ(r.first.force[2], 4.0);
  EXPECT_DOUBLE_EQ(r.first.torque[0], 0.01);
  EXPECT_DOUBLE_EQ(r.first.penetration_depth, 0.002);
  EXPECT_EQ(r.first.contact_count, 2);
  EXPECT_EQ(r.first.flags, 32);
  EXPECT_FALSE(matcher.records()[0].answered());

  listener.HandleWrench(w, 6000);  // a repeat is not a new first answer
  EXPECT_EQ(listener.first_answers(), 1);
  EXPECT_EQ(matcher.repeat_answers(), 1);
}

}  // namespace
}  // namespace probes

namespace probes {
namespace {

constexpr int64_t kOurs = 0x1111, kTheirs = 0x2222;

haptics_msgs::wrench_t WrenchFor(int64_t session, int64_t seq, int64_t utime, int32_t flags = 0) {
  haptics_msgs::wrench_t w{};
  w.pose_session = session;
  w.pose_seq = seq;
  w.pose_utime = utime;
  w.flags = flags;
  return w;
}

TEST(ReplayListener, AnswersToAnotherSendersLiveStreamWhileSendingAreCounted) {
  SeqMatcher matcher(0, 3, kOurs);
  ReplayListener listener(&matcher);
  // Before we send anything another stream is none of our business.
  listener.HandleWrench(WrenchFor(kTheirs, 0, 100), 100);
  EXPECT_EQ(matcher.other_stream_answers(), 0);
  matcher.MarkSent(0, 1000);
  // Same seq and utime as ours but another sender's session: not our answer.
  listener.HandleWrench(WrenchFor(kTheirs, 0, 1000), 1100);
  EXPECT_EQ(matcher.other_stream_answers(), 1);
  EXPECT_EQ(matcher.other_stream_session(), kTheirs);
  EXPECT_FALSE(matcher.records()[0].answered());
  // A silent previous stream ramping down (watchdog) is not "rendering them".
  listener.HandleWrench(WrenchFor(kTheirs, 5, 50, haptics_msgs::wrench_t::FLAG_WATCHDOG), 1200);
  EXPECT_EQ(matcher.other_stream_answers(), 1);
  listener.HandleWrench(WrenchFor(kOurs, 0, 1000), 1300);
  EXPECT_TRUE(matcher.records()[0].answered());
  matcher.MarkSent(1, 2000);
  matcher.MarkSent(2, 3000);
  // After our last pose, plus the tail, another sender may take over.
  listener.HandleWrench(WrenchFor(kTheirs, 7, 7), 3000 + SeqMatcher::kSendingTailUs + 1);
  EXPECT_EQ(matcher.other_stream_answers(), 1);
}

TEST(ReplayListener, StatusesThatShowUsRejectedOrAnotherSourceAreCounted) {
  SeqMatcher matcher(0, 2, kOurs);
  ReplayListener listener(&matcher);
  haptics_msgs::server_status_t status{};
  status.source_session = kTheirs;
  status.source_device = "probe_sim";
  status.last_rejected_session = kOurs;
  listener.HandleStatus(status, 500);  // before sending: ignored
  matcher.MarkSent(0, 1000);
  listener.HandleStatus(status, 1000 + ReplayListener::kStatusSettleUs / 2);  // settling: ignored
  EXPECT_EQ(listener.statuses_rejecting_us(), 0);
  EXPECT_EQ(listener.statuses_other_source(), 0);
  listener.HandleStatus(status, 1000 + ReplayListener::kStatusSettleUs + 1);
  EXPECT_EQ(listener.statuses_rejecting_us(), 1);
  EXPECT_EQ(listener.statuses_other_source(), 1);
  EXPECT_EQ(listener.other_source(), "0x0000000000002222 'probe_sim'");
  // Rendering us, someone else rejected: nothing counted.
  status.source_session = kOurs;
  status.last_rejected_session = kTheirs;
  listener.HandleStatus(status, 1000 + ReplayListener::kStatusSettleUs + 2);
  EXPECT_EQ(listener.statuses_rejecting_us(), 1);
  EXPECT_EQ(listener.statuses_other_source(), 1);
}

}  // namespace
}  // namespace probes
