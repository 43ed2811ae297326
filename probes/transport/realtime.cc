#include "probes/transport/realtime.h"

#include <pthread.h>
#include <sched.h>

#include <cstring>

namespace probes {

bool TryRealtime(int priority, std::string* why) {
  sched_param param{};
  param.sched_priority = priority;
  const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (err != 0) {
    if (why != nullptr) *why = std::string("SCHED_FIFO refused: ") + std::strerror(err);
    return false;
  }
  return true;
}

}  // namespace probes
