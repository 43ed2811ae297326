#include "haptics/loop/timing_stats.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace haptics {
namespace {

// Nearest rank: the smallest sample with at least p*n samples at or below it.
size_t Rank(double p, size_t n) {
  const double r = std::ceil(p * static_cast<double>(n));
  return static_cast<size_t>(std::clamp(r, 1.0, static_cast<double>(n))) - 1;
}

}  // namespace

SampleWindow::SampleWindow(size_t capacity)
    : samples_(std::max<size_t>(capacity, 1)), scratch_(std::max<size_t>(capacity, 1)) {}

void SampleWindow::Add(double x) {
  samples_[next_] = x;
  next_ = (next_ + 1) % samples_.size();
  size_ = std::min(size_ + 1, samples_.size());
}

TimingSummary SampleWindow::Summarize() {
  TimingSummary s;
  s.count = static_cast<int64_t>(size_);
  if (size_ == 0) return s;
  std::copy(samples_.begin(), samples_.begin() + size_, scratch_.begin());
  const auto first = scratch_.begin(), last = scratch_.begin() + size_;
  auto at = [&](double p) {
    auto nth = first + Rank(p, size_);
    std::nth_element(first, nth, last);
    return *nth;
  };
  s.p50 = at(0.50);
  s.p99 = at(0.99);
  s.max = *std::max_element(first, last);
  return s;
}

DurationHistogram::DurationHistogram(int max_us) : bins_(std::max(max_us, 1) + 1, 0) {}

void DurationHistogram::Add(double us) {
  if (!(us >= 0.0)) us = 0.0;
  const size_t last = bins_.size() - 1;
  const size_t bin = us >= static_cast<double>(last) ? last : static_cast<size_t>(us);
  ++bins_[bin];
  ++count_;
  max_ = std::max(max_, us);
}

double DurationHistogram::Percentile(double p) const {
  if (count_ == 0) return 0.0;
  const int64_t rank = static_cast<int64_t>(Rank(p, static_cast<size_t>(count_))) + 1;
  int64_t seen = 0;
  for (size_t b = 0; b < bins_.size(); ++b) {
    seen += bins_[b];
    if (seen >= rank) return b + 1 == bins_.size() ? max_ : std::min(max_, static_cast<double>(b + 1));
  }
  return max_;
}

double DurationHistogram::PercentileFloor(double p) const {
  if (count_ == 0) return 0.0;
  const int64_t rank = static_cast<int64_t>(Rank(p, static_cast<size_t>(count_))) + 1;
  int64_t seen = 0;
  for (size_t b = 0; b < bins_.size(); ++b) {
    seen += bins_[b];
    if (seen >= rank) return b + 1 == bins_.size() ? max_ : static_cast<double>(b);
  }
  return max_;
}

TickLog::TickLog(size_t capacity) : records_(capacity) {}

void TickLog::Add(const TickRecord& r) {
  if (size_ < records_.size()) {
    records_[size_++] = r;
  } else {
    ++not_logged_;
  }
}

bool TickLog::WriteCsv(const std::string& path, double nominal_period_us, std::string* error) const {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) {
    *error = "cannot write timing log '" + path + "': " + std::strerror(errno);
    return false;
  }
  std::fprintf(f, "# nominal_period_us=%.3f ticks_logged=%zu ticks_not_logged=%lld\n", nominal_period_us,
               size_, static_cast<long long>(not_logged_));
  std::fprintf(f, "tick,period_us,compute_us,contact_count,flags,missed\n");
  for (size_t i = 0; i < size_; ++i) {
    const TickRecord& r = records_[i];
    std::fprintf(f, "%zu,%.3f,%.3f,%d,%d,%d\n", i, r.period_us, r.compute_us, r.contact_count, r.flags,
                 r.missed ? 1 : 0);
  }
  const bool ok = std::ferror(f) == 0;
  if (std::fclose(f) != 0 || !ok) {
    *error = "error writing timing log '" + path + "': " + std::strerror(errno);
    return false;
  }
  return true;
}

}  // namespace haptics
