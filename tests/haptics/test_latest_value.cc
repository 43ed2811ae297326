#include "haptics/loop/latest_value.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

namespace haptics {
namespace {

TEST(LatestValue, GivesTheNewestOnceAndCountsDrops) {
  LatestValue<int> v;
  EXPECT_EQ(v.TakeNewest(), nullptr);
  EXPECT_FALSE(v.Write(1));
  const int* p = v.TakeNewest();
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(*p, 1);
  EXPECT_EQ(v.TakeNewest(), nullptr);  // nothing new
  EXPECT_FALSE(v.Write(2));
  EXPECT_TRUE(v.Write(3));  // 2 was never taken: dropped
  EXPECT_TRUE(v.Write(4));
  p = v.TakeNewest();
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(*p, 4);
  EXPECT_EQ(v.TakeNewest(), nullptr);
}

// A payload whose fields must always agree: a torn read would show.
struct Payload {
  int64_t seq = 0;
  double a[16] = {};
};

TEST(LatestValue, ReaderNeverSeesATornOrOlderValue) {
  LatestValue<Payload> v;
  constexpr int64_t kWrites = 200000;
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (int64_t i = 1; i <= kWrites; ++i) {
      Payload& slot = v.WriteSlot();
      slot.seq = i;
      for (double& x : slot.a) x = static_cast<double>(i);
      v.Publish();
    }
    done = true;
  });
  int64_t last = 0, taken = 0, torn = 0, backwards = 0;
  while (!done.load() || last < kWrites) {
    if (const Payload* p = v.TakeNewest()) {
      ++taken;
      for (double x : p->a) torn += x != static_cast<double>(p->seq);
      backwards += p->seq <= last;
      last = p->seq;
    }
  }
  writer.join();
  EXPECT_EQ(torn, 0);
  EXPECT_EQ(backwards, 0);
  EXPECT_EQ(last, kWrites);
  EXPECT_GT(taken, 0);
}

}  // namespace
}  // namespace haptics
