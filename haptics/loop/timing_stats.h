#pragma once
// Timing statistics for the servo loop, preallocated so that recording a
// sample never allocates: a window of recent samples (percentiles by
// nth_element on a preallocated copy), a whole-run histogram, and an optional
// per-tick log of fixed capacity (TickLog, for haptic_server --timing-log).
#include <cstddef>
#include <cstdint>
#include <string>
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
  // The same percentile as the lower edge of its bin: exact for integer
  // samples (e.g. ages in ticks).
  double PercentileFloor(double p) const;

 private:
  std::vector<int64_t> bins_;
  int64_t count_ = 0;
  double max_ = 0.0;
};

// One servo tick, as kept by TickLog. Times in microseconds.
struct TickRecord {
  float period_us = 0.0f;     // wake-up to wake-up (0 for the first tick)
  float compute_us = 0.0f;    // wake-up to after the wrench was handed over
  int32_t contact_count = 0;  // contact regions this tick (WrenchOutput)
  int32_t flags = 0;          // WrenchOutput::flags (kFlag* bits)
  bool missed = false;        // finished after the next tick's start
};

// The per-tick timing log behind haptic_server --timing-log: a fixed number
// of records allocated at construction, so Add never allocates; ticks past
// the capacity are counted in not_logged(), not stored.
class TickLog {
 public:
  explicit TickLog(size_t capacity);  // allocates here only
  void Add(const TickRecord& r);
  size_t size() const { return size_; }
  size_t capacity() const { return records_.size(); }
  int64_t not_logged() const { return not_logged_; }
  const TickRecord& operator[](size_t i) const { return records_[i]; }
  // Writes a CSV: one '#' comment line (nominal period, records, ticks not
  // logged), then the header tick,period_us,compute_us,contact_count,flags,
  // missed and one row per record. Returns false and sets *error (naming
  // the file) if the file cannot be written.
  bool WriteCsv(const std::string& path, double nominal_period_us, std::string* error) const;

 private:
  std::vector<TickRecord> records_;
  size_t size_ = 0;
  int64_t not_logged_ = 0;
};

}  // namespace haptics
