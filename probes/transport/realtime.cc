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

ScopedRealtime::ScopedRealtime(int priority) {
  sched_param previous{};
  if (const int err = pthread_getschedparam(pthread_self(), &previous_policy_, &previous); err != 0) {
    why_ = std::string("pthread_getschedparam: ") + std::strerror(err);
    return;
  }
  previous_priority_ = previous.sched_priority;
  granted_ = TryRealtime(priority, &why_);
}

ScopedRealtime::~ScopedRealtime() {
  if (!granted_) return;
  sched_param previous{};
  previous.sched_priority = previous_priority_;
  pthread_setschedparam(pthread_self(), previous_policy_, &previous);  // lowering is always allowed
}

}  // namespace probes
