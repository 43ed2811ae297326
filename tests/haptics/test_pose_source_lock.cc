// The pose source lock: one sender rendered, others rejected while it is
// alive, takeover after silence, pins, identity changes.
#include "haptics/io/pose_source_lock.h"

#include <gtest/gtest.h>

#include <string>

namespace haptics {
namespace {

constexpr int64_t kMs = 1'000'000;             // ns
constexpr int64_t kRelease = 100 * kMs;        // watchdog 50 ms + ramp 50 ms

const SenderId kA = SenderId::Make(0x1111, "sigma7");
const SenderId kB = SenderId::Make(0x2222, "probe_sim");

TEST(PoseSourceLock, LocksTheFirstValidSenderAndRejectsOthersWhileItIsAlive) {
  PoseSourceLock lock(kRelease);
  EXPECT_FALSE(lock.locked());
  SourceEvent e = lock.Observe(kA, true, 0);
  EXPECT_EQ(e.decision, SourceDecision::kLocked);
  EXPECT_TRUE(e.new_sender);
  EXPECT_EQ(lock.source(), kA);
  EXPECT_EQ(lock.locks(), 1);
  // Interleaved at 1 kHz: A always accepted, B always rejected.
  for (int i = 1; i < 1000; ++i) {
    EXPECT_EQ(lock.Observe(kA, true, i * kMs).decision, SourceDecision::kAccept);
    e = lock.Observe(kB, true, i * kMs + kMs / 2);
    EXPECT_EQ(e.decision, SourceDecision::kRejectOtherSender);
    EXPECT_EQ(e.new_sender, i == 1) << "each sender is reported new exactly once";
  }
  EXPECT_EQ(lock.rejections().other_sender, 999);
  EXPECT_EQ(lock.rejections().total(), 999);
  EXPECT_EQ(lock.locks(), 1);
  EXPECT_EQ(lock.senders_seen(), 2);
}

TEST(PoseSourceLock, InvalidPosesNeitherLockNorKeepTheStreamAlive) {
  PoseSourceLock lock(kRelease);
  // Nobody locked: an invalid pose is passed on (the validator counts it), locks nothing.
  EXPECT_EQ(lock.Observe(kB, false, 0).decision, SourceDecision::kAccept);
  EXPECT_FALSE(lock.locked());
  EXPECT_EQ(lock.Observe(kA, true, 1 * kMs).decision, SourceDecision::kLocked);
  // A sends only garbage from now on: still A's (passed on), but it no longer
  // keeps the stream alive, so B takes over once A's last valid pose is old.
  for (int64_t t = 2 * kMs; t < 1 * kMs + kRelease; t += kMs) {
    EXPECT_EQ(lock.Observe(kA, false, t).decision, SourceDecision::kAccept);
    EXPECT_EQ(lock.Observe(kB, true, t).decision, SourceDecision::kRejectOtherSender);
  }
  EXPECT_EQ(lock.Observe(kB, true, 1 * kMs + kRelease).decision, SourceDecision::kLocked);
  EXPECT_EQ(lock.source(), kB);
}

TEST(PoseSourceLock, TakeoverOnlyAfterTheLockedStreamIsSilentForTheReleaseTime) {
  PoseSourceLock lock(kRelease);
  lock.Observe(kA, true, 0);
  lock.Observe(kA, true, 10 * kMs);  // A's last pose
  EXPECT_TRUE(lock.alive(10 * kMs + kRelease - 1));
  EXPECT_EQ(lock.Observe(kB, true, 10 * kMs + kRelease - 1).decision, SourceDecision::kRejectOtherSender);
  EXPECT_FALSE(lock.alive(10 * kMs + kRelease));
  // Silence long enough: B takes over, and then A is the stranger.
  EXPECT_EQ(lock.Observe(kB, true, 10 * kMs + kRelease).decision, SourceDecision::kLocked);
  EXPECT_EQ(lock.source(), kB);
  EXPECT_EQ(lock.locks(), 2);
  EXPECT_EQ(lock.Observe(kA, true, 10 * kMs + kRelease + 1).decision, SourceDecision::kRejectOtherSender);
}

TEST(PoseSourceLock, TheLockedSenderResumingAfterSilenceIsNotANewLock) {
  PoseSourceLock lock(kRelease);
  lock.Observe(kA, true, 0);
  EXPECT_EQ(lock.Observe(kA, true, 10 * kRelease).decision, SourceDecision::kAccept);
  EXPECT_EQ(lock.locks(), 1);
}

TEST(PoseSourceLock, ASenderThatChangesItsSessionMidStreamIsANewSender) {
  PoseSourceLock lock(kRelease);
  const SenderId before = SenderId::Make(0x1111, "sigma7");
  const SenderId after = SenderId::Make(0x9999, "sigma7");  // same device, new session
  const SenderId renamed = SenderId::Make(0x1111, "sigma7-left");  // same session, other device
  lock.Observe(before, true, 0);
  int64_t t = kMs;
  SourceEvent e = lock.Observe(after, true, t);
  EXPECT_EQ(e.decision, SourceDecision::kRejectOtherSender);
  EXPECT_TRUE(e.new_sender);
  EXPECT_EQ(lock.Observe(renamed, true, t).decision, SourceDecision::kRejectOtherSender);
  // It keeps sending under its new id: rejected until the old stream's
  // release time has passed, then it takes over as a new lock.
  for (t = 2 * kMs; t < kRelease; t += kMs) {
    EXPECT_EQ(lock.Observe(after, true, t).decision, SourceDecision::kRejectOtherSender) << t;
  }
  EXPECT_EQ(lock.Observe(after, true, kRelease).decision, SourceDecision::kLocked);
  EXPECT_EQ(lock.source(), after);
  EXPECT_EQ(lock.locks(), 2);
}

TEST(PoseSourceLock, SessionZeroHasNoIdentityAndIsAlwaysRejected) {
  PoseSourceLock lock(kRelease);
  const SenderId anonymous = SenderId::Make(0, "old_client");
  EXPECT_EQ(lock.Observe(anonymous, true, 0).decision, SourceDecision::kRejectNoIdentity);
  EXPECT_FALSE(lock.locked());
  EXPECT_EQ(lock.rejections().no_identity, 1);
}

TEST(PoseSourceLock, APinAcceptsOnlyTheNamedSessionOrDevice) {
  PoseSourcePin by_session;
  by_session.session = 0x2222;
  PoseSourceLock lock(kRelease, by_session);
  // A is first and valid but not the pinned session: never locked, even when B is silent.
  EXPECT_EQ(lock.Observe(kA, true, 0).decision, SourceDecision::kRejectNotPinned);
  EXPECT_FALSE(lock.locked());
  EXPECT_EQ(lock.Observe(kB, true, kMs).decision, SourceDecision::kLocked);
  EXPECT_EQ(lock.Observe(kA, true, 100 * kRelease).decision, SourceDecision::kRejectNotPinned);
  EXPECT_EQ(lock.rejections().not_pinned, 2);
  EXPECT_EQ(lock.rejections().other_sender, 0);

  PoseSourcePin by_device;
  by_device.device = "sigma7";
  PoseSourceLock device_lock(kRelease, by_device);
  EXPECT_EQ(device_lock.Observe(kB, true, 0).decision, SourceDecision::kRejectNotPinned);
  EXPECT_EQ(device_lock.Observe(kA, true, 0).decision, SourceDecision::kLocked);
  // Another session of the pinned device is still one-at-a-time.
  EXPECT_EQ(device_lock.Observe(SenderId::Make(0x3333, "sigma7"), true, kMs).decision,
            SourceDecision::kRejectOtherSender);
}

TEST(PoseSourceLock, SendersBeyondTheTableAreStillHandledJustNotReportedNew) {
  PoseSourceLock lock(kRelease);
  lock.Observe(kA, true, 0);
  for (int64_t s = 1; s <= 200; ++s) {
    const SourceEvent e = lock.Observe(SenderId::Make(0x10000 + s, "x"), true, kMs);
    EXPECT_EQ(e.decision, SourceDecision::kRejectOtherSender);
  }
  EXPECT_EQ(lock.senders_seen(), static_cast<int64_t>(PoseSourceLock::kSendersRemembered));
  EXPECT_EQ(lock.rejections().other_sender, 200);
}

TEST(SenderIdentity, SessionsPrintAsHexAndParseBack) {
  EXPECT_EQ(haptics_msgs::FormatSession(0x2a), "0x000000000000002a");
  EXPECT_EQ(haptics_msgs::FormatSession(-1), "0xffffffffffffffff");
  int64_t s = 0;
  ASSERT_TRUE(haptics_msgs::ParseSession("0xffffffffffffffff", &s));
  EXPECT_EQ(s, -1);
  ASSERT_TRUE(haptics_msgs::ParseSession("42", &s));
  EXPECT_EQ(s, 42);
  ASSERT_TRUE(haptics_msgs::ParseSession("0x000000000000002A", &s));
  EXPECT_EQ(s, 42);
  for (const char* bad : {"", "0", "0x0", "-5", "+5", "0x", "12abc", "0x1ffffffffffffffff",
                          "18446744073709551616", " 1"}) {
    EXPECT_FALSE(haptics_msgs::ParseSession(bad, &s)) << bad;
  }
  const int64_t a = haptics_msgs::NewSession(), b = haptics_msgs::NewSession();
  EXPECT_NE(a, 0);
  EXPECT_NE(a, b);
}

TEST(SenderIdentity, DeviceNamesAreCutToTheLimit) {
  const SenderId id = SenderId::Make(1, std::string(100, 'x'));
  EXPECT_EQ(id.device_name().size(), kMaxDeviceNameBytes);
}

}  // namespace
}  // namespace haptics
