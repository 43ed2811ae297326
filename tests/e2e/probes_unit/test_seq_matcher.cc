// Seq matcher: answers are matched to sent poses by pose_seq and pose_utime.
#include <gtest/gtest.h>

#include <stdexcept>

#include "probes/results/seq_matcher.h"

namespace probes {
namespace {

WrenchAnswer AnswerTo(int64_t seq, int64_t utime, double fz = 0.0) {
  WrenchAnswer a;
  a.pose_seq = seq;
  a.pose_utime = utime;
  a.force[2] = fz;
  return a;
}

TEST(SeqMatcher, FirstAnswerGivesLatencyAndWrench) {
  SeqMatcher m(100, 3);
  m.MarkSent(101, 5000);
  EXPECT_EQ(m.Match(AnswerTo(101, 5000, 2.5), 5120), SeqMatcher::Outcome::kFirstAnswer);
  const PoseRecord& r = m.records()[1];
  EXPECT_EQ(r.seq, 101);
  EXPECT_TRUE(r.answered());
  EXPECT_EQ(r.latency_us, 120);
  EXPECT_DOUBLE_EQ(r.first.force[2], 2.5);
  EXPECT_FALSE(m.records()[0].answered());
  EXPECT_FALSE(m.records()[2].answered());
}

TEST(SeqMatcher, RepeatAnswerKeepsFirstLatencyAndWrench) {
  SeqMatcher m(0, 1);
  m.MarkSent(0, 1000);
  m.Match(AnswerTo(0, 1000, 1.0), 1100);
  EXPECT_EQ(m.Match(AnswerTo(0, 1000, 9.0), 2100), SeqMatcher::Outcome::kRepeatAnswer);
  EXPECT_EQ(m.records()[0].answers, 2);
  EXPECT_EQ(m.records()[0].latency_us, 100);
  EXPECT_DOUBLE_EQ(m.records()[0].first.force[2], 1.0);
  EXPECT_EQ(m.repeat_answers(), 1);
}

TEST(SeqMatcher, NoPoseYetIsCountedSeparately) {
  SeqMatcher m(0, 2);
  EXPECT_EQ(m.Match(AnswerTo(-1, 0), 10), SeqMatcher::Outcome::kNoPose);
  EXPECT_EQ(m.no_pose_answers(), 1);
  EXPECT_EQ(m.foreign_answers(), 0);
}

TEST(SeqMatcher, ForeignAnswersDoNotMatch) {
  SeqMatcher m(10, 2);
  m.MarkSent(10, 500);
  // Outside the range, not sent yet, and a reused seq with another utime.
  EXPECT_EQ(m.Match(AnswerTo(9, 500), 600), SeqMatcher::Outcome::kForeign);
  EXPECT_EQ(m.Match(AnswerTo(12, 500), 600), SeqMatcher::Outcome::kForeign);
  EXPECT_EQ(m.Match(AnswerTo(11, 500), 600), SeqMatcher::Outcome::kForeign);
  EXPECT_EQ(m.Match(AnswerTo(10, 499), 600), SeqMatcher::Outcome::kForeign);
  EXPECT_EQ(m.foreign_answers(), 4);
  EXPECT_FALSE(m.records()[0].answered());
  EXPECT_EQ(m.Match(AnswerTo(10, 500), 600), SeqMatcher::Outcome::kFirstAnswer);
}

TEST(SeqMatcher, MarkSentOutsideRangeThrows) {
  SeqMatcher m(5, 2);
  EXPECT_THROW(m.MarkSent(4, 1), std::out_of_range);
  EXPECT_THROW(m.MarkSent(7, 1), std::out_of_range);
  EXPECT_NO_THROW(m.MarkSent(6, 1));
}

}  // namespace
}  // namespace probes
