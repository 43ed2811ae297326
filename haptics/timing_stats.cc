#include "haptics/timing_stats.h"

#include <algorithm>
#include <cmath>

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

}  // namespace haptics
