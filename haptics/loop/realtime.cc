#include "haptics/loop/realtime.h"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

namespace haptics {

bool TrySetFifoScheduling(int priority, std::string* why) {
  sched_param param{};
  param.sched_priority = priority;
  const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (err != 0) {
    *why = std::string("pthread_setschedparam(SCHED_FIFO, ") + std::to_string(priority) +
           "): " + std::strerror(err);
    return false;
  }
  return true;
}

bool TrySetNormalScheduling(std::string* why) {
  sched_param param{};
  param.sched_priority = 0;
  const int err = pthread_setschedparam(pthread_self(), SCHED_OTHER, &param);
  if (err != 0) {
    *why = std::string("pthread_setschedparam(SCHED_OTHER): ") + std::strerror(err);
    return false;
  }
  return true;
}

bool TryPinToCpu(int cpu, std::string* why) {
  if (cpu < 0 || cpu >= CPU_SETSIZE) {
    *why = "cpu " + std::to_string(cpu) + " out of range";
    return false;
  }
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  const int err = pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
  if (err != 0) {
    *why = "pthread_setaffinity_np(cpu " + std::to_string(cpu) + "): " + std::strerror(err);
    return false;
  }
  return true;
}

ScopedCpuPin::ScopedCpuPin(int cpu) {
  static_assert(sizeof(cpu_set_t) <= sizeof(saved_));
  cpu_set_t* saved = reinterpret_cast<cpu_set_t*>(saved_);
  const int err = pthread_getaffinity_np(pthread_self(), sizeof(cpu_set_t), saved);
  if (err != 0) {
    why_ = std::string("pthread_getaffinity_np: ") + std::strerror(err);
    return;
  }
  ok_ = TryPinToCpu(cpu, &why_);
}

ScopedCpuPin::~ScopedCpuPin() {
  if (ok_) pthread_setaffinity_np(pthread_self(), sizeof(cpu_set_t), reinterpret_cast<cpu_set_t*>(saved_));
}

bool TryLockMemory(std::string* why) {
  if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    *why = std::string("mlockall: ") + std::strerror(errno);
    return false;
  }
  return true;
}

namespace {

// Writes one byte per page of `bytes` of stack below the caller's frame: a
// chunk per call, the deeper calls first (not a tail call, so every frame
// stays on the stack while the next one is below it).
[[gnu::noinline]] void TouchStack(size_t bytes) {
  constexpr size_t kChunk = 16 * 1024;
  volatile unsigned char chunk[kChunk];
  if (bytes > kChunk) TouchStack(bytes - kChunk);
  for (size_t i = 0; i < kChunk; i += 4096) chunk[i] = 0;
}

}  // namespace

void PrefaultThread(size_t stack_bytes) {
  TouchStack(stack_bytes);
  // The thread's arena and tcache come with its first allocation.
  void* p = std::malloc(4096);
  if (p != nullptr) std::memset(p, 0, 4096);
  asm volatile("" : : "r"(p) : "memory");  // keeps the compiler from eliding the pair
  std::free(p);
}

void NameThisThread(const char* name) { pthread_setname_np(pthread_self(), name); }

int NumCpus() {
  const long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : 1;
}

}  // namespace haptics
