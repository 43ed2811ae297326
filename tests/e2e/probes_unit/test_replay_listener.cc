// ReplayListener without LCM: wrenches are matched to sent poses, status
// messages are kept, and either marks the server as seen. (Not over memq://:
// LCM 1.3.1's typed-subscription callback trips UBSan's vptr check in
// sanitizer builds.)
#include <gtest/gtest.h>

#include "haptics_msgs/server_status_t.hpp"
#include "haptics_msgs/wrench_t.hpp"
#include "probes/replay_listener.h"

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
