// PhaseLock: the servo tick's phase follows pose arrival at a fixed rate.
#include "haptics/loop/phase_lock.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace haptics {
namespace {

constexpr double kPeriodUs = 1000.0;

// Simulates a device sending a pose every period at `arrival_phase_us` and a
// loop ticking every period plus PhaseLock's shift. Returns the wait of the
// last pose taken after `ticks` ticks.
double SimulateLock(PhaseLock* lock, double arrival_phase_us, double tick_phase_us, int ticks,
                    double* max_period_change_us) {
  double wait = 0.0;
  *max_period_change_us = 0.0;
  for (int k = 0; k < ticks; ++k) {
    // Newest arrival at or before the tick (arrivals at phase + n T).
    wait = std::fmod(tick_phase_us - arrival_phase_us + 100 * kPeriodUs, kPeriodUs);
    const double shift = lock->Update(wait);
    *max_period_change_us = std::max(*max_period_change_us, std::abs(shift));
    tick_phase_us += shift;  // next tick: one period plus the shift later
  }
  return wait;
}

TEST(PhaseLock, LocksToTheTargetWaitFromAnyStartingPhase) {
  for (double start : {0.0, 50.0, 149.0, 151.0, 400.0, 999.0}) {
    PhaseLock lock({}, kPeriodUs);
    double max_change = 0.0;
    const double wait = SimulateLock(&lock, /*arrival=*/start, /*tick=*/0.0, 2000, &max_change);
    EXPECT_NEAR(wait, lock.options().target_us, 1.0) << "arrival phase " << start;
    // The rate never moves by more than max_step per period.
    EXPECT_LE(max_change, lock.options().max_step_us + 1e-12);
  }
}

TEST(PhaseLock, DisabledNeverShifts) {
  PhaseLockOptions options;
  options.enabled = false;
  PhaseLock lock(options, kPeriodUs);
  double max_change = 0.0;
  const double wait = SimulateLock(&lock, 600.0, 0.0, 500, &max_change);
  EXPECT_DOUBLE_EQ(max_change, 0.0);
  EXPECT_NEAR(wait, 400.0, 1e-9);
  EXPECT_EQ(lock.updates(), 0);
}

TEST(PhaseLock, JitteredArrivalsStayLockedWithSmallShifts) {
  // Locked (tick 150 us after the mean arrival at phase 300), then arrivals
  // jitter by up to +-40 us: waits stay within target +- (jitter + a few
  // steps) and no pose misses its tick (which would show as a wait near T).
  PhaseLock locked({}, kPeriodUs);
  double tick = 300.0 + 150.0;
  double worst = 0.0;
  for (int k = 0; k < 5000; ++k) {
    const double jitter = 40.0 * std::sin(0.7 * k) * std::cos(0.13 * k);
    const double wait = std::fmod(tick - (300.0 + jitter) + 100 * kPeriodUs, kPeriodUs);
    worst = std::max(worst, std::abs(wait - 150.0));
    tick += locked.Update(wait);
  }
  EXPECT_LT(worst, 60.0);
}

TEST(PhaseLock, RejectsBadOptionsNamingThem) {
  PhaseLockOptions options;
  options.target_us = 1200.0;  // beyond the period
  try {
    PhaseLock lock(options, kPeriodUs);
    FAIL() << "accepted target_us beyond the period";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("target_us 1200"), std::string::npos) << e.what();
  }
  options = {};
  options.max_step_us = 200.0;
  EXPECT_THROW(PhaseLock(options, kPeriodUs), std::invalid_argument);
}

TEST(PhaseLock, IgnoresNonFiniteWaitsAndMovesLaterForANegativeLead) {
  PhaseLock lock({}, kPeriodUs);
  EXPECT_EQ(lock.Update(std::nan("")), 0.0);
  EXPECT_EQ(lock.updates(), 0);
  // Pose-triggered ticks feed the pose's lead on the deadline: a pose after
  // the deadline (negative lead) moves the deadline later, by at most a step.
  EXPECT_EQ(lock.Update(-5.0), lock.options().max_step_us);
  EXPECT_EQ(lock.updates(), 1);
}

}  // namespace
}  // namespace haptics
