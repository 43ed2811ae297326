#pragma once
// Timing statistics for the servo loop, preallocated so that recording a
// sample never allocates: a window of recent samples (percentiles by
// nth_element on a preallocated copy) and a whole-run histogram.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace haptics {

struct TimingSummary {
  int64_t count = 0;
  double p50 = 0.0, p99 = 0.0, max = 0.0;  // same unit as the samples
};

// The last `capacity` samples.
class SampleWindow {
 public:
  explicit SampleWindow(size_t capacity);  // allocates here only
  void Add(double x);
  void Clear() { size_ = 0, next_ = 0; }
  size_t size() const { return size_; }
  // Nearest-rank percentiles of the current contents (zeros when empty).
  TimingSummary Summarize();

 private:
  std::vector<double> samples_;
  std::vector<double> scratch_;
  size_t size_ = 0, next_ = 0;
};

// Non-negative durations in microseconds, 1 us bins up to max_us; larger
// samples land in an overflow bin (their percentile reads as the max seen).
class DurationHistogram {
 public:
  explicit DurationHistogram(int max_us = 20000);
  void Add(double us);
  int64_t count() const { return count_; }
  double max() const { return max_; }
  // Nearest-rank percentile, p in (0, 1]; the upper edge of its bin.
  double Percentile(double p) const;

 private:
  std::vector<int64_t> bins_;
  int64_t count_ = 0;
  double max_ = 0.0;
};

}  // namespace haptics
