#include "haptics/haptic_renderer.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "alloc_counter.h"
#include "haptics_test_util.h"

namespace haptics {
namespace {

using test::MakePose;
constexpr double kDt = 1e-3;

struct Rig {
  SceneConfig config;
  SceneModels models;
  std::unique_ptr<HapticRenderer> renderer;
  double t = 0.0;
  int64_t seq = 0;

  explicit Rig(SceneConfig c = test::BoxOnBoxConfig(), const pd::PolyDepthOptions& pd = {})
      : config(std::move(c)), models(BuildSceneModels(config)),
        renderer(std::make_unique<HapticRenderer>(config, models, pd)) {}

  const WrenchOutput& Tick(const PoseSample* pose) {
    const WrenchOutput& out = renderer->Tick(t, pose);
    t += kDt;
    return out;
  }
  const WrenchOutput& TickAt(const Vector3& p, const Quaternion& q = Quaternion::Identity()) {
    const PoseSample pose = MakePose(++seq, p, q);
    return Tick(&pose);
  }
};

TEST(HapticRenderer, ZeroAndStaleUntilTheFirstValidPose) {
  Rig rig;
  for (int i = 0; i < 10; ++i) {
    const WrenchOutput& out = rig.Tick(nullptr);
    EXPECT_EQ(out.pose_seq, -1);
    EXPECT_EQ(out.wrench.f_W, Vector3::Zero());
    EXPECT_TRUE(out.flags & kFlagStaleInput);
    EXPECT_EQ(out.tick, i + 1);
  }
  EXPECT_FALSE(rig.renderer->engaged());
  // An invalid pose does not engage either.
  PoseSample bad = MakePose(1, Vector3(std::numeric_limits<double>::quiet_NaN(), 0, 0));
  EXPECT_EQ(rig.Tick(&bad).pose_seq, -1);
  EXPECT_FALSE(rig.renderer->engaged());
  const WrenchOutput& out = rig.TickAt(Vector3(0, 0, 0.03));
  EXPECT_TRUE(rig.renderer->engaged());
  EXPECT_EQ(out.pose_seq, rig.seq);
  EXPECT_EQ(out.pose_utime, 1000 * rig.seq);
  EXPECT_FALSE(out.flags & kFlagStaleInput);
  EXPECT_TRUE(rig.renderer->tool().X_W.isApprox(rig.renderer->device().X_W));
}

TEST(HapticRenderer, ToolFollowsInFreeSpaceWithSmallForces) {
  Rig rig;
  // Move the handle 2 cm along x at 10 cm/s, 2 cm above the table.
  for (int i = 0; i <= 200; ++i) rig.TickAt(Vector3(0.0001 * i - 0.01, 0, 0.03));
  for (int i = 0; i < 300; ++i) rig.TickAt(Vector3(0.01, 0, 0.03));
  EXPECT_LT((rig.renderer->tool().X_W.translation() - Vector3(0.01, 0, 0.03)).norm(), 1e-6);
  EXPECT_LT(rig.renderer->output().wrench.f_W.norm(), 1e-3);
  EXPECT_EQ(rig.renderer->contact().num_in_contact, 0);
}

TEST(HapticRenderer, PressingIntoTheTableRendersTheSeriesSpring) {
  Rig rig;
  rig.TickAt(Vector3(0, 0, 0.02));
  // The handle sinks to where the box's bottom would be 1 cm into the table.
  for (int i = 0; i < 200; ++i) rig.TickAt(Vector3(0, 0, 0.02 - 0.0001 * i));
  const WrenchOutput* out = nullptr;
  for (int i = 0; i < 2000; ++i) out = &rig.TickAt(Vector3(0, 0, 0.0));
  // k_t (z_T - z_D) = k_c (1 cm - z_T) => z_T = 7.5 mm, force 7.5 N upward.
  EXPECT_NEAR(rig.renderer->tool().X_W.translation().z(), 0.0075, 1e-6);
  EXPECT_NEAR(out->wrench.f_W.z(), 7.5, 1e-3);
  EXPECT_NEAR(out->wrench.f_W.head<2>().norm(), 0.0, 1e-6);
  EXPECT_NEAR(out->penetration_depth, 0.0025, 1e-6);
  EXPECT_GT(out->contact_count, 0);
  EXPECT_EQ(out->flags & (kFlagForceSaturated | kFlagPdInvalid | kFlagStaleInput), 0);
}

TEST(HapticRenderer, SoftEngageRampsTheOutputAtStart) {
  // Two identical runs, with and without a 0.2 s soft engage. The handle
  // starts 5 mm into the table: the tool starts in contact and is pushed out.
  SceneConfig soft_config = test::BoxOnBoxConfig();
  soft_config.servo.soft_engage_s = 0.2;
  Rig soft(soft_config), hard;
  int compared = 0;
  for (int i = 0; i < 400; ++i) {
    const WrenchOutput s = soft.TickAt(Vector3(0, 0, 0.005));
    const WrenchOutput h = hard.TickAt(Vector3(0, 0, 0.005));
    if (i < 199) {
      EXPECT_TRUE(s.flags & kFlagSoftEngage) << i;
    }
    if (i > 201) {
      EXPECT_FALSE(s.flags & kFlagSoftEngage) << i;
    }
    EXPECT_FALSE(h.flags & kFlagSoftEngage);
    const int32_t nonlinear = kFlagRateLimited | kFlagForceSaturated | kFlagTorqueSaturated;
    if (((s.flags | h.flags) & nonlinear) == 0) {
      // The tool is simulated identically; only the output is scaled, by t / T.
      const double scale = std::min(1.0, i / 200.0);
      EXPECT_LT((s.wrench.f_W - scale * h.wrench.f_W).norm(), 1e-9) << i;
      ++compared;
    }
  }
  EXPECT_GT(compared, 300);
  EXPECT_EQ(soft.renderer->output().wrench.f_W, hard.renderer->output().wrench.f_W);
  EXPECT_GT(hard.renderer->output().wrench.f_W.z(), 1.0);
}

TEST(HapticRenderer, StaleAndRejectedPosesKeepTheLastGoodOne) {
  Rig rig;
  rig.TickAt(Vector3(0.01, 0, 0.03));
  const int64_t good_seq = rig.seq;
  PoseSample outside = MakePose(++rig.seq, Vector3(0.5, 0, 0));
  PoseSample zero_q = MakePose(++rig.seq, Vector3(0, 0, 0), Quaternion(0, 0, 0, 0));
  EXPECT_EQ(rig.Tick(&outside).pose_seq, good_seq);
  EXPECT_EQ(rig.Tick(&zero_q).pose_seq, good_seq);
  const WrenchOutput& stale = rig.Tick(nullptr);
  EXPECT_TRUE(stale.flags & kFlagStaleInput);
  EXPECT_EQ(stale.pose_seq, good_seq);
  const RendererCounts c = rig.renderer->counts();
  EXPECT_EQ(c.poses_rejected.outside_workspace, 1);
  EXPECT_EQ(c.poses_rejected.bad_quaternion, 1);
  EXPECT_EQ(c.poses_accepted, 1);
  EXPECT_EQ(c.stale_ticks, 3);
  EXPECT_TRUE(rig.renderer->device().X_W.translation().isApprox(Vector3(0.01, 0, 0.03)));
}

TEST(HapticRenderer, WatchdogRampsTheOutputToZero) {
  SceneConfig config = test::BoxOnBoxConfig();
  config.servo.watchdog_timeout_s = 0.02;
  config.servo.watchdog_ramp_s = 0.03;
  Rig rig(config);
  rig.TickAt(Vector3(0, 0, 0.02));
  for (int i = 0; i < 500; ++i) rig.TickAt(Vector3(0, 0, 0.003));  // pressing: about 5 N
  ASSERT_GT(rig.renderer->output().wrench.f_W.norm(), 1.0);
  // Poses stop: within timeout + ramp (+1 tick) the output is exactly zero.
  const WrenchOutput* out = nullptr;
  for (int i = 0; i < 52; ++i) out = &rig.Tick(nullptr);
  EXPECT_TRUE(out->flags & kFlagWatchdog);
  EXPECT_EQ(out->wrench.f_W, Vector3::Zero());
  EXPECT_EQ(out->wrench.tau_W, Vector3::Zero());
  EXPECT_EQ(rig.renderer->counts().watchdog_trips, 1);
}

TEST(HapticRenderer, ANewSenderSessionReEngagesFromZeroWithTheToolAtItsHandle) {
  SceneConfig config = test::BoxOnBoxConfig();
  config.servo.soft_engage_s = 0.1;
  Rig rig(config);
  auto from = [&](int64_t session, const Vector3& p) {
    PoseSample pose = MakePose(++rig.seq, p);
    pose.session = session;
    return rig.Tick(&pose);
  };
  for (int i = 0; i < 500; ++i) from(0xa, Vector3(0, 0, 0.003));  // A presses: about 5 N
  ASSERT_GT(rig.renderer->output().wrench.f_W.z(), 3.0);
  EXPECT_EQ(rig.renderer->output().pose_session, 0xa);
  // A falls silent; the receiver hands B over only after the watchdog timeout
  // plus the ramp (pose_source_lock.h), when the force is zero.
  const int silent_ticks =
      static_cast<int>((config.servo.watchdog_timeout_s + config.servo.watchdog_ramp_s) / kDt) + 2;
  for (int i = 0; i < silent_ticks; ++i) rig.Tick(nullptr);
  ASSERT_EQ(rig.renderer->output().wrench.f_W, Vector3::Zero());
  // B's first pose, 5 cm away in free space: the tool appears at B's handle
  // (not dragged over from A's), the force starts from zero.
  const Vector3 p_B(0.05, -0.05, 0.04);
  const WrenchOutput& first = from(0xb, p_B);
  EXPECT_EQ(first.pose_session, 0xb);
  EXPECT_TRUE(first.flags & kFlagSoftEngage);
  EXPECT_FALSE(first.flags & kFlagForceSaturated);
  EXPECT_LT(first.wrench.f_W.norm(), 1e-9);
  EXPECT_LT((rig.renderer->tool().X_W.translation() - p_B).norm(), 1e-3);
  double max_force = 0.0;
  for (int i = 0; i < 300; ++i) max_force = std::max(max_force, from(0xb, p_B).wrench.f_W.norm());
  EXPECT_LT(max_force, 0.5);  // free space, holding still
  EXPECT_EQ(rig.renderer->counts().source_changes, 1);
  EXPECT_EQ(rig.renderer->counts().limiter.saturated, 0);
}

TEST(HapticRenderer, UnverifiedPdRaisesTheFlag) {
  pd::PolyDepthOptions crippled;
  crippled.num_maximally_clear = 0;
  crippled.use_centroid = false;
  crippled.num_random = 0;
  crippled.num_sampling_directions = 0;
  // Box meshes (thin plates), so that the pair is solved by PolyDepth.
  SceneConfig config = test::BoxOnBoxConfig();
  config.tool.shape.shape = ThinPlateShape{0.01, 0.01, 0.01};
  config.objects[0].shape.shape = ThinPlateShape{0.05, 0.05, 0.01};
  Rig rig(config, crippled);
  const WrenchOutput& out = rig.TickAt(Vector3(0, 0, 0.008));  // tool in the table
  EXPECT_TRUE(out.flags & kFlagPdInvalid);
  EXPECT_EQ(rig.renderer->counts().pd_invalid, 1);
  EXPECT_TRUE(out.wrench.AllFinite());
}

// Garbage, jumps, deep penetration, extreme orientations: the output is
// always finite and within the device limits.
TEST(HapticRenderer, NeverOutputsNaNOrExceedsLimits) {
  Rig rig;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double specials[] = {nan, inf, -inf, 1e308, -1e308, 1e-310, 0.0};
  int64_t bad_inputs = 0;
  for (int i = 0; i < 6000; ++i) {
    PoseSample p = MakePose(i, Vector3(0.09 * u(rng), 0.09 * u(rng), 0.06 * u(rng)),
                            Quaternion(u(rng), u(rng), u(rng), u(rng)).normalized());
    switch (i % 10) {
      case 0:  // a special value somewhere
        p.p_WD[i % 3] = specials[(i / 10) % 7];
        ++bad_inputs;
        break;
      case 1:
        p.q_WD.coeffs()[(i / 10) % 4] = specials[(i / 10) % 7];
        break;
      case 2:
        p.has_velocity = true;
        p.v_WD = Vector3(u(rng), specials[(i / 10) % 7], 0);
        p.w_WD = Vector3(1e3 * u(rng), 0, 0);
        break;
      case 3:  // a stale tick
        break;
      default:  // a jump to a random pose, often deep inside the table
        break;
    }
    const WrenchOutput& out = rig.Tick(i % 10 == 3 ? nullptr : &p);
    ASSERT_TRUE(out.wrench.AllFinite()) << "tick " << i;
    ASSERT_TRUE(std::isfinite(out.penetration_depth)) << "tick " << i;
    ASSERT_LE(out.wrench.f_W.norm(), rig.config.device.max_force * (1 + 1e-12)) << i;
    ASSERT_LE(out.wrench.tau_W.norm(), rig.config.device.max_torque * (1 + 1e-12)) << i;
    ASSERT_TRUE(rig.renderer->tool().X_W.matrix().allFinite()) << i;
  }
  EXPECT_GT(bad_inputs, 0);
  EXPECT_GT(rig.renderer->counts().poses_rejected.total(), 0);
  EXPECT_GT(rig.renderer->counts().limiter.saturated, 0);
}

// No heap allocation in a tick once the solvers' scratch has grown: replay
// the same contact trajectory twice and count allocations the second time.
TEST(HapticRenderer, TicksDoNotAllocateAfterWarmUp) {
  Rig rig;
  auto run = [&] {
    rig.seq = 0;
    for (int i = 0; i < 300; ++i) {
      const double z = 0.02 - 0.0001 * i;
      const Quaternion q(Eigen::AngleAxisd(0.002 * i, Vector3(1, 1, 0).normalized()));
      rig.TickAt(Vector3(0.0001 * i, 0, z), q);
      if (i % 7 == 0) rig.Tick(nullptr);
    }
  };
  run();
  const int64_t before = test::ThreadAllocations();
  run();
  EXPECT_EQ(test::ThreadAllocations() - before, 0);
  EXPECT_GT(rig.renderer->geometry().query_count(), 100);
}

}  // namespace
}  // namespace haptics
