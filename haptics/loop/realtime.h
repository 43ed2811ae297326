#pragma once
// Best-effort real-time settings for the calling thread. Each returns whether
// it worked and fills *why with the reason if not; callers log a fallback.
#include <cstddef>
#include <string>

namespace haptics {

// SCHED_FIFO at `priority` (1..99).
bool TrySetFifoScheduling(int priority, std::string* why);
// SCHED_OTHER (undoes a real-time policy inherited from the creating thread).
bool TrySetNormalScheduling(std::string* why);
// Pins the calling thread to one CPU.
bool TryPinToCpu(int cpu, std::string* why);
// Restricts the calling thread to one CPU for the object's lifetime (threads
// it creates meanwhile inherit that CPU), then restores its previous set.
// ok() false (why() says why) if the CPU could not be set; nothing to restore.
class ScopedCpuPin {
 public:
  explicit ScopedCpuPin(int cpu);
  ~ScopedCpuPin();
  ScopedCpuPin(const ScopedCpuPin&) = delete;
  ScopedCpuPin& operator=(const ScopedCpuPin&) = delete;
  bool ok() const { return ok_; }
  const std::string& why() const { return why_; }

 private:
  bool ok_ = false;
  std::string why_;
  alignas(8) unsigned char saved_[128];  // the previous cpu_set_t
};
// Locks current and future pages in RAM (no page faults in the loop).
bool TryLockMemory(std::string* why);
// Stack touched by PrefaultThread by default (the loops use a few KiB).
constexpr size_t kPrefaultStackBytes = 256 * 1024;
// Before a real-time loop: touches the top `stack_bytes` of the calling
// thread's stack and makes its malloc arena (glibc maps one per thread at the
// thread's first allocation: the servo thread's first LCM publish did, 1.3 ms
// of mmap/munmap/mprotect in its first tick), so that the loop neither takes
// page faults on its stack nor maps memory for the first allocations of the
// libraries it calls. Under mlockall(MCL_FUTURE) the pages stay resident.
void PrefaultThread(size_t stack_bytes = kPrefaultStackBytes);
// Online CPUs.
int NumCpus();
// Names the calling thread (15 characters at most), for top -H and debuggers.
void NameThisThread(const char* name);

}  // namespace haptics
