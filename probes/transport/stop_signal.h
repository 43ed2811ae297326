#pragma once
// SIGINT/SIGTERM set a flag that long-running loops poll, so the tools stop
// cleanly (closing their log or printing their summary) when interrupted.
#include <csignal>

namespace probes {

inline volatile std::sig_atomic_t g_stop_requested = 0;

inline void InstallStopSignalHandlers() {
  struct sigaction sa {};
  sa.sa_handler = [](int) { g_stop_requested = 1; };
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

}  // namespace probes
