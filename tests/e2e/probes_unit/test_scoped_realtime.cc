// ScopedRealtime (probes/transport/realtime.h): SCHED_FIFO inside the scope,
// the thread's previous policy after it. probe_replay sends inside one, so
// its summaries and its gnuplot child run at normal priority beside the
// server they measured.
#include "probes/transport/realtime.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <thread>

#include "tests/prerequisites.h"

namespace probes {
namespace {

struct Policy {
  int policy = -1;
  int priority = -1;
};

Policy Current() {
  Policy p;
  sched_param param{};
  pthread_getschedparam(pthread_self(), &p.policy, &param);
  p.priority = param.sched_priority;
  return p;
}

TEST(ScopedRealtime, FifoInsideThePreviousPolicyAfter) {
  // On a fresh thread: the test runner's own policy stays untouched.
  Policy before, inside, after;
  bool granted = false;
  std::string why;
  std::thread([&] {
    before = Current();
    {
      ScopedRealtime scope(42);
      granted = scope.granted();
      why = scope.why();
      inside = Current();
    }
    after = Current();
  }).join();
  if (!granted) {
    // The servo's own tests need SCHED_FIFO too; under CI it must be there.
    if (pd::test::InCi()) GTEST_FAIL() << "SCHED_FIFO refused under CI: " << why;
    GTEST_SKIP() << "SCHED_FIFO refused here: " << why;
  }
  EXPECT_EQ(before.policy, SCHED_OTHER);
  EXPECT_EQ(inside.policy, SCHED_FIFO);
  EXPECT_EQ(inside.priority, 42);
  EXPECT_EQ(after.policy, before.policy);
  EXPECT_EQ(after.priority, before.priority);
}

TEST(ScopedRealtime, RestoresAnEarlierFifoPriority) {
  Policy inside, after;
  bool granted = false;
  std::thread([&] {
    ScopedRealtime outer(30);
    if (!(granted = outer.granted())) return;
    {
      ScopedRealtime inner(50);
      inside = Current();
    }
    after = Current();
  }).join();
  if (!granted) {
    if (pd::test::InCi()) GTEST_FAIL() << "SCHED_FIFO refused under CI";
    GTEST_SKIP() << "SCHED_FIFO refused here";
  }
  EXPECT_EQ(inside.priority, 50);
  EXPECT_EQ(after.policy, SCHED_FIFO);
  EXPECT_EQ(after.priority, 30);
}

}  // namespace
}  // namespace probes
