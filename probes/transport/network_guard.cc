#include "probes/transport/network_guard.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace probes {

std::string LcmProvider(const std::string& url) {
  std::string effective = url;
  if (effective.empty()) {
    const char* env = std::getenv("LCM_DEFAULT_URL");
    effective = env != nullptr ? env : "";
  }
  if (effective.empty()) return "udpm";
  const size_t colon = effective.find("://");
  return colon == std::string::npos ? effective : effective.substr(0, colon);
}

std::vector<std::string> NonLoopbackInterfaces() {
  std::ifstream in("/proc/self/net/dev");
  if (!in) throw std::runtime_error("cannot read /proc/self/net/dev to check the network namespace");
  std::vector<std::string> names;
  std::string line;
  while (std::getline(in, line)) {
    // Data lines look like "  eth0: 1234 ..."; the two header lines have no ':' before '|'.
    const size_t colon = line.find(':');
    if (colon == std::string::npos || line.find('|') != std::string::npos) continue;
    std::istringstream name_stream(line.substr(0, colon));
    std::string name;
    name_stream >> name;
    if (!name.empty() && name != "lo") names.push_back(name);
  }
  return names;
}

void RequireIsolatedNetworkForUdpm(const std::string& url, const std::string& program) {
  if (LcmProvider(url) != "udpm") return;
  const char* allow = std::getenv("PROBES_ALLOW_HOST_NETWORK");
  if (allow != nullptr && std::string(allow) == "1") return;
  const std::vector<std::string> interfaces = NonLoopbackInterfaces();
  if (interfaces.empty()) return;
  std::string list;
  for (const std::string& name : interfaces) list += (list.empty() ? "" : ", ") + name;
  throw std::runtime_error(
      program + ": refusing LCM udpm:// (URL '" + (url.empty() ? "<default>" : url) +
      "'): this network namespace has interfaces other than loopback (" + list +
      "), so multicast could leave the machine. Run inside a private network namespace: "
      "scripts/netns_run.sh " + program + " ... (or use memq:// in-process; set "
      "PROBES_ALLOW_HOST_NETWORK=1 only for a deliberate real-device setup)");
}

}  // namespace probes
