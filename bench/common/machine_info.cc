#include "bench/common/machine_info.h"

#include <array>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <thread>

#include "pd_build/build_info.h"

namespace pd_bench {
namespace {

std::string Trim(std::string s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  const auto e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

// First line of a shell command's stdout, "" on failure.
std::string RunCommand(const std::string& cmd) {
  std::string out;
  if (FILE* f = popen(cmd.c_str(), "r")) {
    std::array<char, 256> buf{};
    if (fgets(buf.data(), buf.size(), f)) out = buf.data();
    pclose(f);
  }
  return Trim(out);
}

}  // namespace

std::string ReadLoadAverage() {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  f >> a >> b >> c;
  return a + " " + b + " " + c;
}

MachineInfo ReadMachineInfo(const std::string& source_dir) {
  MachineInfo m;
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      m.cpu_model = Trim(line.substr(line.find(':') + 1));
      break;
    }
  }
  if (m.cpu_model.empty()) m.cpu_model = "unknown";
  m.num_cpus = static_cast<int>(std::thread::hardware_concurrency());

  const std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
  m.date_utc = date;

  const std::string git = "git -C '" + source_dir + "' ";
  m.git_commit = RunCommand(git + "rev-parse --short HEAD 2>/dev/null");
  if (m.git_commit.empty()) m.git_commit = "unknown";
  // Uncommitted changes mean the hash alone does not identify the code measured
  // (the committed reports in bench/results are outputs, not code).
  else if (!RunCommand(git + "status --porcelain --untracked-files=no -- . ':!bench/results' "
                             "2>/dev/null").empty())
    m.git_commit += "-dirty";
  m.build_type = std::string(pd_build::kBuildType) + ", " + pd_build::kCpuLevel;
  m.compiler = pd_build::Compiler();
  m.load_average = ReadLoadAverage();
  return m;
}

std::string MachineMarkdown(const MachineInfo& m) {
  return "- CPU: " + m.cpu_model + " (" + std::to_string(m.num_cpus) +
         " logical CPUs), load average at the end " + ReadLoadAverage() + "\n- date " + m.date_utc +
         ", commit " + m.git_commit + ", build " + m.build_type + ", " + m.compiler + "\n";
}

}  // namespace pd_bench
