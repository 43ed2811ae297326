// Pose order anomalies: the pure monitor, the receiver's counters over
// memq:// (no network), and their way into the status message.
#include "haptics/io/pose_sequence.h"

#include <gtest/gtest.h>

#include <limits>
#include <tuple>

#include "haptics/io/lcm_io.h"

namespace haptics {
namespace {

TEST(PoseSequence, ClassifiesDuplicatesSkipsAndTimeGoingBack) {
  PoseSequenceMonitor m;
  auto obs = [&](int64_t seq, int64_t utime) { return m.Observe(seq, utime); };
  PoseSequenceEvent e = obs(10, 1000);  // first: never an anomaly
  EXPECT_FALSE(e.out_of_order || e.time_backwards || e.skipped);
  e = obs(11, 2000);
  EXPECT_FALSE(e.out_of_order || e.time_backwards || e.skipped);
  e = obs(11, 3000);  // duplicate seq
  EXPECT_TRUE(e.out_of_order);
  EXPECT_EQ(e.skipped, 0);
  e = obs(15, 4000);  // 12, 13, 14 missing
  EXPECT_FALSE(e.out_of_order);
  EXPECT_EQ(e.skipped, 3);
  e = obs(16, 3500);  // clock back
  EXPECT_TRUE(e.time_backwards);
  EXPECT_FALSE(e.out_of_order);
  e = obs(0, 0);  // sender restarted: one anomaly, then followed normally
  EXPECT_TRUE(e.out_of_order && e.time_backwards);
  e = obs(1, 1000);
  EXPECT_FALSE(e.out_of_order || e.time_backwards || e.skipped);
  // Extremes do not overflow.
  e = obs(std::numeric_limits<int64_t>::max(), std::numeric_limits<int64_t>::max());
  EXPECT_EQ(e.skipped, std::numeric_limits<int64_t>::max() - 2);
  e = obs(std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::min());
  EXPECT_TRUE(e.out_of_order && e.time_backwards);
  e = obs(std::numeric_limits<int64_t>::max(), 0);
  EXPECT_EQ(e.skipped, std::numeric_limits<int64_t>::max());  // saturated
}

void Publish(lcm::LCM* lcm, int64_t seq, int64_t utime) {
  haptics_msgs::probe_pose_t m{};
  m.version = haptics_msgs::probe_pose_t::VERSION;
  m.sender_session = 0x5e55;
  m.sender_device = "test";
  m.seq = seq;
  m.utime = utime;
  m.orientation[0] = 1.0;
  lcm->publish("PROBE_POSE", &m);
}

TEST(PoseSequence, ReceiverCountsThemAndTheStatusCarriesThem) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  LatestValue<PoseSample> poses;
  PoseReceiver receiver(&lcm, "PROBE_POSE", &poses);
  // 1 2 2(dup) 5(skips 3,4) 4(back) 6 with utime going back once.
  const int64_t seqs[] = {1, 2, 2, 5, 4, 6};
  const int64_t utimes[] = {1000, 2000, 2000, 5000, 4000, 6000};
  for (int i = 0; i < 6; ++i) {
    Publish(&lcm, seqs[i], utimes[i]);
    while (lcm.handleTimeout(0) > 0) {
    }
  }
  const ReceiverCounts c = receiver.counts();
  EXPECT_EQ(c.received, 6);  // all still handed over
  EXPECT_EQ(c.out_of_order, 2);
  EXPECT_EQ(c.seq_skipped, 2 + 1);  // 3, 4; then 5 after 4
  EXPECT_EQ(c.time_backwards, 1);
  ASSERT_NE(poses.TakeNewest(), nullptr);
  const haptics_msgs::server_status_t m = MakeStatusMessage(LoopStatus{}, c);
  // received, out of order, skipped, time backwards
  EXPECT_EQ(std::make_tuple(m.poses_received, m.poses_out_of_order, m.pose_seq_skipped,
                            m.pose_time_backwards),
            std::make_tuple(int64_t{6}, int64_t{2}, int64_t{3}, int64_t{1}));
}

}  // namespace
}  // namespace haptics
