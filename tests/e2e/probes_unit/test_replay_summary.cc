// Replay summary: counts, extremes and the pass/fail verdict.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "probes/results/replay_summary.h"

namespace probes {
namespace {

PoseRecord Answered(int64_t seq, int64_t latency, double fz) {
  PoseRecord r;
  r.seq = seq;
  r.send_us = 1000 * seq;
  r.answers = 1;
  r.latency_us = latency;
  r.first.pose_seq = seq;
  r.first.force[2] = fz;
  r.first.torque[0] = 0.1 * fz;
  return r;
}

SummaryLimits Limits(double force_limit_N, double max_superseded = 0.0) {
  SummaryLimits l;
  l.force_limit_N = force_limit_N;
  l.max_superseded_fraction = max_superseded;
  return l;
}

PoseRecord SentOnly(int64_t seq) {
  PoseRecord r;
  r.seq = seq;
  r.send_us = 1000 * seq;
  return r;
}

TEST(ReplaySummary, AllAnsweredIsOk) {
  const std::vector<PoseRecord> records = {Answered(0, 100, 1.0), Answered(1, 300, -4.0)};
  const ReplaySummary s = Summarise(records, 2, Limits(5.0));
  EXPECT_TRUE(s.ok());
  EXPECT_EQ(s.poses_sent, 2);
  EXPECT_EQ(s.answered, 2);
  EXPECT_DOUBLE_EQ(s.max_force_N, 4.0);
  EXPECT_DOUBLE_EQ(s.max_torque_Nm, 0.4);
  EXPECT_DOUBLE_EQ(s.latency_us.max, 300.0);
  EXPECT_DOUBLE_EQ(s.duration_s, 0.001);
}

TEST(ReplaySummary, UnansweredAndUnsentFail) {
  // Pose 1 sent but never answered, and nothing after it: lost. Pose 2 never sent.
  const std::vector<PoseRecord> records = {Answered(0, 100, 0.0), SentOnly(1), PoseRecord{}};
  const ReplaySummary s = Summarise(records, 3, Limits(10.0, 0.5));
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.unanswered, 1);
  EXPECT_EQ(s.lost, 1);
  EXPECT_EQ(s.superseded, 0);
  EXPECT_EQ(s.poses_sent, 2);
  ASSERT_EQ(s.failures().size(), 2u);
  EXPECT_NE(s.failures()[0].find("sent 2 of 3"), std::string::npos);
  EXPECT_NE(s.failures()[1].find("1 poses unanswered at the end"), std::string::npos);
}

TEST(ReplaySummary, SupersededPosesFailUnlessTolerated) {
  // 1, 2 and 4 unanswered with later answers: superseded, longest run 2.
  const std::vector<PoseRecord> records = {Answered(0, 100, 0.0), SentOnly(1), SentOnly(2),
                                           Answered(3, 100, 0.0), SentOnly(4),
                                           Answered(5, 100, 0.0)};
  const ReplaySummary strict = Summarise(records, 6, {});
  EXPECT_EQ(strict.superseded, 3);
  EXPECT_EQ(strict.lost, 0);
  EXPECT_EQ(strict.longest_unanswered_run, 2);
  EXPECT_FALSE(strict.ok());
  EXPECT_NE(strict.failures()[0].find("3 poses unanswered while later ones were answered"), std::string::npos);
  EXPECT_TRUE(Summarise(records, 6, Limits(10.0, 0.5)).ok());    // 3 <= 0.5 * 6
  EXPECT_FALSE(Summarise(records, 6, Limits(10.0, 0.4)).ok());   // 3 > 2.4
}

TEST(ReplaySummary, NonFiniteAndOverLimitFail) {
  std::vector<PoseRecord> records = {Answered(0, 100, 6.0), Answered(1, 100, 1.0)};
  records[1].first.torque[1] = std::numeric_limits<double>::quiet_NaN();
  const ReplaySummary s = Summarise(records, 2, Limits(5.0));
  EXPECT_EQ(s.non_finite_answers, 1);
  EXPECT_EQ(s.over_force_limit, 1);
  EXPECT_DOUBLE_EQ(s.max_force_N, 6.0);  // the NaN answer does not count in the max
  EXPECT_FALSE(s.ok());
  EXPECT_TRUE(Summarise(records, 2, {}).over_force_limit == 0);
}

TEST(ReplaySummary, AnotherSenderBeingRenderedFailsTheRunEvenWithEveryPoseAnswered) {
  const std::vector<PoseRecord> records = {Answered(0, 100, 1.0), Answered(1, 300, 1.0)};
  ReplaySummary s = Summarise(records, 2, Limits(5.0));
  ASSERT_TRUE(s.ok());
  s.other_stream_answers = 3;
  s.other_stream = "0x0000000000002222";
  s.statuses_rejecting_us = 1;
  s.statuses_other_source = 2;
  s.other_source = "0x0000000000002222 'probe_sim'";
  EXPECT_FALSE(s.ok());
  ASSERT_EQ(s.failures().size(), 3u);
  EXPECT_NE(s.failures()[0].find("3 wrenches rendered another sender's stream (0x0000000000002222)"),
            std::string::npos) << s.failures()[0];
  EXPECT_NE(s.failures()[1].find("the server rejected this replay's poses"), std::string::npos);
  EXPECT_NE(s.failures()[2].find("pose source was 0x0000000000002222 'probe_sim'"), std::string::npos);
  EXPECT_EQ(ToJson(s)["other_stream_answers"], 3);
}

TEST(ReplaySummary, JsonHasNullLatencyWhenNothingAnswered) {
  PoseRecord r;
  r.send_us = 5;
  const nlohmann::ordered_json j = ToJson(Summarise({r}, 1, {}));
  EXPECT_FALSE(j["ok"].get<bool>());
  EXPECT_TRUE(j["latency_us"]["p50"].is_null());
  EXPECT_EQ(j["unanswered"].get<int>(), 1);
  EXPECT_TRUE(j["server_status"].is_null());
}

}  // namespace
}  // namespace probes
