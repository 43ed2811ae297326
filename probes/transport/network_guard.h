#pragma once
// Safety net for LCM over UDP multicast: udpm:// must only be used where no
// packet can leave the machine, i.e. inside a private network namespace whose
// only interface is loopback (scripts/netns_run.sh makes one). Every probe
// tool checks this before creating its LCM instance.
#include <string>
#include <vector>

namespace probes {

// Provider part of an LCM URL ("udpm", "memq", "file", ...). An empty URL
// means $LCM_DEFAULT_URL, and if that is unset LCM's default, which is udpm.
std::string LcmProvider(const std::string& url);

// Network interfaces other than "lo" visible to this process, read from
// /proc/self/net/dev (per network namespace, unlike /sys/class/net).
std::vector<std::string> NonLoopbackInterfaces();

// Throws std::runtime_error with an explanation when `url` uses udpm and a
// non-loopback interface is visible, unless the environment variable
// PROBES_ALLOW_HOST_NETWORK=1 is set (for a deliberate real-device setup).
void RequireIsolatedNetworkForUdpm(const std::string& url, const std::string& program);

}  // namespace probes
