#pragma once
// A one-line progress bar on stderr for long benchmark stages. Redraws at most
// ten times a second so printing never shows up in the timings.
#include <chrono>
#include <string>

namespace pd_bench {

class Progress {
 public:
  Progress(std::string label, int total);
  ~Progress();  // completes the line
  void Tick(int n = 1);

 private:
  void Draw(bool force);
  std::string label_;
  int total_, done_ = 0;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace pd_bench
