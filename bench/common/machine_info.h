#pragma once
// Facts about the machine and source tree a benchmark ran on, read at run time
// so that every report names the hardware, date and commit it measured.
#include <string>

namespace pd_bench {

struct MachineInfo {
  std::string cpu_model;   // /proc/cpuinfo "model name"
  int num_cpus = 0;        // logical CPUs online
  std::string date_utc;    // ISO 8601
  std::string git_commit;  // `git rev-parse --short HEAD` (+ "-dirty" if modified)
  std::string build_type;  // CMAKE_BUILD_TYPE and CPU level of this binary ("Release, x86-64-v3")
  std::string compiler;
  std::string load_average;  // /proc/loadavg at the time of the call
};

MachineInfo ReadMachineInfo(const std::string& source_dir);
std::string ReadLoadAverage();

// The two Markdown bullet lines every report starts with: CPU and load
// average now; date, commit, build type and compiler.
std::string MachineMarkdown(const MachineInfo& m);

}  // namespace pd_bench
