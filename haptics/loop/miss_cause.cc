#include "haptics/loop/miss_cause.h"

#include <algorithm>

namespace haptics {

MissCause MissClassifier::Classify(const TickTimes& t, int64_t work) {
  // Half a period, not the period: a witness that fit only just says little
  // about the same work overrunning by a hair; one that took half the time
  // says the overrun came from elsewhere.
  if (work >= 0 && 2 * t.cpu_ns <= period_ns_) max_witness_work_ = std::max(max_witness_work_, work);
  if (t.end_ns <= t.deadline_ns) return MissCause::kNone;
  // Would it have fit had it started on time?
  if (t.scheduled_ns + (t.end_ns - t.wake_ns) <= t.deadline_ns) return MissCause::kLateWakeup;
  if (t.scheduled_ns + t.cpu_ns <= t.deadline_ns) return MissCause::kStalled;
  if (work >= 0 && work <= max_witness_work_) return MissCause::kCharged;
  return MissCause::kCompute;
}

}  // namespace haptics
