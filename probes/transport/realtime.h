#pragma once
// Optional SCHED_FIFO for the periodic sender and the echo: it shortens the
// latency tail on a loaded machine. Refusal is reported, never fatal.
#include <string>

namespace probes {

// Returns true if the calling thread now runs SCHED_FIFO at `priority`
// (1..99); otherwise false and *why says what the kernel answered.
bool TryRealtime(int priority, std::string* why);

}  // namespace probes
