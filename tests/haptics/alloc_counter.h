#pragma once
// Counts heap allocations made by the current thread (global operator new is
// replaced in alloc_counter.cc), to check that a servo tick does not allocate.
#include <cstdint>

namespace haptics::test {

int64_t ThreadAllocations();

}  // namespace haptics::test
