#pragma once
// Best-effort real-time settings for the calling thread. Each returns whether
// it worked and fills *why with the reason if not; callers log a fallback.
#include <string>

namespace haptics {

// SCHED_FIFO at `priority` (1..99).
bool TrySetFifoScheduling(int priority, std::string* why);
// SCHED_OTHER (undoes a real-time policy inherited from the creating thread).
bool TrySetNormalScheduling(std::string* why);
// Pins the calling thread to one CPU.
bool TryPinToCpu(int cpu, std::string* why);
// Locks current and future pages in RAM (no page faults in the loop).
bool TryLockMemory(std::string* why);
// Online CPUs.
int NumCpus();
// Names the calling thread (15 characters at most), for top -H and debuggers.
void NameThisThread(const char* name);

}  // namespace haptics
