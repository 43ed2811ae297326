#pragma once
// Optional SCHED_FIFO for the periodic sender and the echo: it shortens the
// latency tail on a loaded machine. Refusal is reported, never fatal.
#include <string>

namespace probes {

// Returns true if the calling thread now runs SCHED_FIFO at `priority`
// (1..99); otherwise false and *why says what the kernel answered.
bool TryRealtime(int priority, std::string* why);

// SCHED_FIFO at `priority` for the calling thread while in scope, then the
// thread's previous policy again. The sender needs it while it sends; what
// follows (summaries, CSV, the gnuplot child that inherits the policy) must
// not run at a real-time priority beside the server it measured, where it
// would starve the server's normal-priority geometry thread.
class ScopedRealtime {
 public:
  // Refusal is kept in why() and granted() is false; never fatal.
  explicit ScopedRealtime(int priority);
  ~ScopedRealtime();
  ScopedRealtime(const ScopedRealtime&) = delete;
  ScopedRealtime& operator=(const ScopedRealtime&) = delete;

  bool granted() const { return granted_; }
  const std::string& why() const { return why_; }

 private:
  bool granted_ = false;
  int previous_policy_ = 0;
  int previous_priority_ = 0;
  std::string why_;
};

}  // namespace probes
