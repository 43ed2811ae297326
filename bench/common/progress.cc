#include "bench/common/progress.h"

#include <algorithm>
#include <cstdio>

namespace pd_bench {

Progress::Progress(std::string label, int total)
    : label_(std::move(label)), total_(std::max(total, 1)),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {
  Draw(true);
}

Progress::~Progress() {
  done_ = total_;
  Draw(true);
  std::fputc('\n', stderr);
}

void Progress::Tick(int n) {
  done_ = std::min(total_, done_ + n);
  Draw(false);
}

void Progress::Draw(bool force) {
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  constexpr int kWidth = 30;
  const int filled = kWidth * done_ / total_;
  const double elapsed_s = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "\r%-40.40s [%.*s%*s] %3d%% %6.1f s", label_.c_str(), filled,
               "##############################", kWidth - filled, "", 100 * done_ / total_,
               elapsed_s);
  std::fflush(stderr);
}

}  // namespace pd_bench
