// PrefaultThread (realtime.h): after it, a real-time loop's first use of its
// stack (and its first small allocations) take no page faults. Measured with
// the thread's own minor-fault count (getrusage RUSAGE_THREAD), on threads
// whose stacks are fresh mappings (never touched, so the control thread shows
// the faults the prefault removes).
#include "haptics/loop/realtime.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sys/mman.h>
#include <sys/resource.h>

#include <cstdlib>
#include <thread>
#include <cstring>

namespace haptics {
namespace {

constexpr size_t kUse = 192 * 1024;  // stack the "loop" uses: 48 pages

long MinorFaults() {
  rusage u{};
  getrusage(RUSAGE_THREAD, &u);
  return u.ru_minflt;
}

[[gnu::noinline]] void UseStack(size_t bytes) {
  constexpr size_t kChunk = 8 * 1024;
  volatile unsigned char chunk[kChunk];
  if (bytes > kChunk) UseStack(bytes - kChunk);
  for (size_t i = 0; i < kChunk; i += 512) chunk[i] = static_cast<unsigned char>(i);
}

struct Run {
  bool prefault = false;
  long faults = -1;
};

void* Loop(void* arg) {
  Run* run = static_cast<Run*>(arg);
  if (run->prefault) PrefaultThread();
  const long before = MinorFaults();
  UseStack(kUse);
  void* p = std::malloc(512);
  std::memset(p, 1, 512);
  std::free(p);
  run->faults = MinorFaults() - before;
  return nullptr;
}

// Runs Loop on a thread whose 1 MiB stack is a fresh anonymous mapping.
long FaultsOnFreshThread(bool prefault) {
  constexpr size_t kStack = 1 << 20;
  void* stack = mmap(nullptr, kStack, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  EXPECT_NE(stack, MAP_FAILED);
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstack(&attr, stack, kStack);
  Run run{prefault};
  pthread_t thread;
  EXPECT_EQ(pthread_create(&thread, &attr, &Loop, &run), 0);
  pthread_join(thread, nullptr);
  pthread_attr_destroy(&attr);
  munmap(stack, kStack);
  return run.faults;
}

TEST(Realtime, PrefaultedThreadTakesNoPageFaultsInItsLoop) {
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer moves locals to fake stacks and serves malloc from its
  // own allocator, both faulting in fresh pages of their own: the property
  // measured here is the production build's (CI runs it there).
  GTEST_SKIP() << "AddressSanitizer build: its fake stacks and allocator fault by design";
#endif
  const long cold = FaultsOnFreshThread(false);
  const long prefaulted = FaultsOnFreshThread(true);
  // The control run faults in (nearly) every page it touches: the measure works.
  EXPECT_GE(cold, static_cast<long>(kUse / 4096) - 4) << "prefaulted " << prefaulted;
  EXPECT_LE(prefaulted, 1) << "without the prefault " << cold;
}

// ScopedCpuPin: a thread created inside the scope runs on the pinned CPU only
// (how the server keeps the LCM threads on the servo's CPU); the creating
// thread gets its own CPUs back after the scope.
TEST(Realtime, ScopedCpuPinPinsThreadsCreatedInsideAndRestoresTheCreator) {
  cpu_set_t before;
  ASSERT_EQ(pthread_getaffinity_np(pthread_self(), sizeof(before), &before), 0);
  int cpu = -1;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &before)) cpu = c;  // the last allowed CPU
  ASSERT_GE(cpu, 0);
  cpu_set_t child{};
  {
    ScopedCpuPin pin(cpu);
    ASSERT_TRUE(pin.ok()) << pin.why();
    std::thread t([&child] { pthread_getaffinity_np(pthread_self(), sizeof(child), &child); });
    t.join();
  }
  EXPECT_EQ(CPU_COUNT(&child), 1);
  EXPECT_TRUE(CPU_ISSET(cpu, &child));
  cpu_set_t after;
  ASSERT_EQ(pthread_getaffinity_np(pthread_self(), sizeof(after), &after), 0);
  EXPECT_TRUE(CPU_EQUAL(&before, &after));
  EXPECT_FALSE(ScopedCpuPin(CPU_SETSIZE + 5).ok());
}

}  // namespace
}  // namespace haptics
