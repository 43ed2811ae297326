#include "haptics/tool/wrench_limiter.h"

#include <gtest/gtest.h>

#include <limits>

#include "haptics/io/wrench_output.h"
#include "haptics_test_util.h"

namespace haptics {
namespace {

constexpr double kDt = 1e-3;

DeviceConfig Device() { return test::BoxOnBoxConfig().device; }  // 12 N, 0.2 N·m, 2000 N/s, 33 N·m/s

// Drives the limiter toward `target` until the rate limit lets it arrive.
Wrench Settle(WrenchLimiter* limiter, const Wrench& target, int32_t* flags) {
  Wrench out;
  for (int i = 0; i < 1000; ++i) {
    *flags = 0;
    out = limiter->Apply(target, 1.0, flags);
  }
  return out;
}

TEST(WrenchLimiter, ClampsForceMagnitudeKeepingDirection) {
  WrenchLimiter limiter(Device(), kDt);
  const Wrench big{Vector3(30, -40, 0), Vector3::Zero()};  // 50 N
  int32_t flags = 0;
  const Wrench out = Settle(&limiter, big, &flags);
  EXPECT_NEAR(out.f_W.norm(), 12.0, 1e-12);
  EXPECT_TRUE(out.f_W.normalized().isApprox(big.f_W.normalized(), 1e-12));
  EXPECT_TRUE(flags & kFlagForceSaturated);
  EXPECT_FALSE(flags & kFlagTorqueSaturated);
  EXPECT_EQ(limiter.counts().force_saturated, 1000);
  EXPECT_EQ(limiter.counts().saturated, 1000);
  EXPECT_EQ(limiter.counts().torque_saturated, 0);
}

TEST(WrenchLimiter, ClampsTorqueMagnitudeKeepingDirection) {
  WrenchLimiter limiter(Device(), kDt);
  const Wrench big{Vector3::Zero(), Vector3(0, 0.3, -0.4)};  // 0.5 N·m
  int32_t flags = 0;
  const Wrench out = Settle(&limiter, big, &flags);
  EXPECT_NEAR(out.tau_W.norm(), 0.2, 1e-12);
  EXPECT_TRUE(out.tau_W.normalized().isApprox(big.tau_W.normalized(), 1e-12));
  EXPECT_TRUE(flags & kFlagTorqueSaturated);
  EXPECT_FALSE(flags & kFlagForceSaturated);
  EXPECT_EQ(limiter.counts().torque_saturated, 1000);
}

TEST(WrenchLimiter, LimitsTheForceRateAndCountsIt) {
  WrenchLimiter limiter(Device(), kDt);
  const Wrench step{Vector3(0, 0, 10), Vector3::Zero()};
  int32_t flags = 0;
  // 2000 N/s * 1 ms = 2 N per tick: 10 N takes 5 ticks.
  for (int i = 1; i <= 4; ++i) {
    flags = 0;
    const Wrench out = limiter.Apply(step, 1.0, &flags);
    EXPECT_NEAR(out.f_W.z(), 2.0 * i, 1e-12);
    EXPECT_TRUE(flags & kFlagRateLimited);
  }
  flags = 0;
  EXPECT_NEAR(limiter.Apply(step, 1.0, &flags).f_W.z(), 10.0, 1e-12);
  EXPECT_FALSE(flags & kFlagRateLimited);  // exactly 2 N: within the limit
  EXPECT_EQ(limiter.counts().rate_limited, 4);
  // Down again: the change is limited the same way.
  flags = 0;
  EXPECT_NEAR(limiter.Apply(Wrench{}, 1.0, &flags).f_W.z(), 8.0, 1e-12);
  EXPECT_TRUE(flags & kFlagRateLimited);
  EXPECT_EQ(limiter.counts().rate_limited, 5);
}

TEST(WrenchLimiter, LimitsTheTorqueRate) {
  WrenchLimiter limiter(Device(), kDt);
  int32_t flags = 0;
  const Wrench out = limiter.Apply({Vector3::Zero(), Vector3(0.1, 0, 0)}, 1.0, &flags);
  EXPECT_NEAR(out.tau_W.x(), 0.033, 1e-12);
  EXPECT_TRUE(flags & kFlagRateLimited);
}

TEST(WrenchLimiter, ScalesBeforeClamping) {
  WrenchLimiter limiter(Device(), kDt);
  int32_t flags = 0;
  const Wrench out = limiter.Apply({Vector3(1.0, 0, 0), Vector3(0, 0.01, 0)}, 0.5, &flags);
  EXPECT_NEAR(out.f_W.x(), 0.5, 1e-15);
  EXPECT_NEAR(out.tau_W.y(), 0.005, 1e-15);
  EXPECT_EQ(flags, 0);
}

TEST(WrenchLimiter, NonFiniteInputNeverReachesTheOutput) {
  WrenchLimiter limiter(Device(), kDt);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  int32_t flags = 0;
  limiter.Apply({Vector3(1, 0, 0), Vector3::Zero()}, 1.0, &flags);
  for (const Wrench& bad : {Wrench{Vector3(nan, 0, 0), Vector3::Zero()},
                            Wrench{Vector3::Zero(), Vector3(0, inf, 0)},
                            Wrench{Vector3(inf, -inf, 0), Vector3(nan, 0, 0)}}) {
    const Wrench out = limiter.Apply(bad, 1.0, &flags);
    EXPECT_TRUE(out.AllFinite());
    EXPECT_EQ(out.f_W, Vector3::Zero());
    EXPECT_EQ(out.tau_W, Vector3::Zero());
  }
  EXPECT_EQ(limiter.counts().nonfinite, 3);
  // And it recovers from zero under the rate limit.
  const Wrench after = limiter.Apply({Vector3(5, 0, 0), Vector3::Zero()}, 1.0, &flags);
  EXPECT_NEAR(after.f_W.x(), 2.0, 1e-12);
}

}  // namespace
}  // namespace haptics
