#include "haptics/contact/engage_envelope.h"

#include <gtest/gtest.h>

#include "haptics/io/wrench_output.h"

namespace haptics {
namespace {

constexpr double kDt = 1e-3;

TEST(EngageEnvelope, ZeroUntilTheFirstPoseThenALinearRamp) {
  EngageEnvelope e(/*soft_engage_s=*/0.5, /*watchdog_timeout_s=*/0.05, /*watchdog_ramp_s=*/0.02);
  int32_t flags = 0;
  for (int i = 0; i < 100; ++i) EXPECT_EQ(e.Update(i * kDt, false, &flags), 0.0);
  EXPECT_FALSE(e.engaged());
  const double t0 = 0.1;
  flags = 0;
  EXPECT_EQ(e.Update(t0, true, &flags), 0.0);
  EXPECT_TRUE(flags & kFlagSoftEngage);
  for (int i = 1; i <= 600; ++i) {
    flags = 0;
    const double t = t0 + i * kDt;
    const double s = e.Update(t, true, &flags);
    const double expected = std::min(1.0, (t - t0) / 0.5);
    EXPECT_NEAR(s, expected, 1e-9) << i;
    EXPECT_EQ((flags & kFlagSoftEngage) != 0, s < 1.0) << i;
    EXPECT_FALSE(flags & kFlagWatchdog);
  }
  EXPECT_EQ(e.scale(), 1.0);
}

TEST(EngageEnvelope, WatchdogRampsToZeroWithinTheConfiguredTime) {
  const double timeout = 0.05, ramp = 0.02;
  EngageEnvelope e(0.0, timeout, ramp);
  int32_t flags = 0;
  double t = 0.0;
  for (int i = 0; i < 100; ++i, t += kDt) e.Update(t, true, &flags);
  ASSERT_EQ(e.scale(), 1.0);
  const double last_pose = t - kDt;
  // Poses stop. Before the timeout nothing changes.
  for (; t < last_pose + timeout - 0.5 * kDt; t += kDt) {
    flags = 0;
    EXPECT_EQ(e.Update(t, false, &flags), 1.0);
    EXPECT_FALSE(flags & kFlagWatchdog);
  }
  // Then it ramps down, reaching zero no later than timeout + ramp (plus the
  // tick that notices the timeout).
  double previous = 1.0;
  for (; t <= last_pose + timeout + ramp + kDt + 1e-9; t += kDt) {
    flags = 0;
    const double s = e.Update(t, false, &flags);
    EXPECT_LE(s, previous);
    previous = s;
  }
  EXPECT_TRUE(flags & kFlagWatchdog);
  EXPECT_EQ(e.scale(), 0.0);
  EXPECT_EQ(e.watchdog_trips(), 1);
  EXPECT_TRUE(e.watchdog_active());
  // Poses resume: ramps back up, counted once.
  flags = 0;
  e.Update(t, true, &flags);
  EXPECT_FALSE(flags & kFlagWatchdog);
  EXPECT_FALSE(e.watchdog_active());
  EXPECT_EQ(e.scale(), 1.0);  // soft_engage_s = 0: immediate
  EXPECT_EQ(e.watchdog_trips(), 1);
}

TEST(EngageEnvelope, RecoveryAfterWatchdogUsesTheSoftEngageRamp) {
  EngageEnvelope e(0.1, 0.01, 0.01);
  int32_t flags = 0;
  double t = 0.0;
  for (int i = 0; i < 200; ++i, t += kDt) e.Update(t, true, &flags);
  for (int i = 0; i < 100; ++i, t += kDt) e.Update(t, false, &flags);
  ASSERT_EQ(e.scale(), 0.0);
  flags = 0;
  e.Update(t, true, &flags);
  t += kDt;
  for (int i = 0; i < 50; ++i, t += kDt) e.Update(t, true, &flags);
  EXPECT_NEAR(e.scale(), 0.51, 1e-9);  // 51 ms into a 100 ms ramp
  EXPECT_TRUE(flags & kFlagSoftEngage);
}

}  // namespace
}  // namespace haptics
