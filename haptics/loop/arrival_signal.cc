#include "haptics/loop/arrival_signal.h"

#include <linux/futex.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <climits>

namespace haptics {
namespace {

// The futex word is the counter itself (std::atomic<uint32_t> is a plain
// 32-bit word on Linux).
uint32_t* Word(std::atomic<uint32_t>* a) { return reinterpret_cast<uint32_t*>(a); }

}  // namespace

void ArrivalSignal::Notify() {
  count_.fetch_add(1, std::memory_order_acq_rel);
  syscall(SYS_futex, Word(&count_), FUTEX_WAKE_PRIVATE, INT_MAX, nullptr, nullptr, 0);
}

bool ArrivalSignal::WaitUntil(uint32_t seen, int64_t deadline_ns) {
  timespec ts;
  ts.tv_sec = deadline_ns / 1'000'000'000;
  ts.tv_nsec = deadline_ns % 1'000'000'000;
  for (;;) {
    if (count_.load(std::memory_order_acquire) != seen) return true;
    // FUTEX_WAIT_BITSET takes an absolute CLOCK_MONOTONIC time.
    const long r = syscall(SYS_futex, Word(&count_), FUTEX_WAIT_BITSET_PRIVATE, seen, &ts, nullptr,
                           FUTEX_BITSET_MATCH_ANY);
    if (r == 0 || errno == EAGAIN) continue;  // woken or changed: re-check
    if (errno == ETIMEDOUT) return count_.load(std::memory_order_acquire) != seen;
    // EINTR: try again until the deadline.
  }
}

}  // namespace haptics
