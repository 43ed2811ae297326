// The udpm guard: provider parsing and refusal outside a loopback-only namespace.
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>

#include "probes/transport/network_guard.h"

namespace probes {
namespace {

TEST(NetworkGuard, Provider) {
  EXPECT_EQ(LcmProvider("memq://"), "memq");
  EXPECT_EQ(LcmProvider("udpm://239.255.76.67:7667?ttl=0"), "udpm");
  EXPECT_EQ(LcmProvider("file:///tmp/x.log?mode=r"), "file");
  unsetenv("LCM_DEFAULT_URL");
  EXPECT_EQ(LcmProvider(""), "udpm");  // LCM's own default
  setenv("LCM_DEFAULT_URL", "memq://", 1);
  EXPECT_EQ(LcmProvider(""), "memq");
  unsetenv("LCM_DEFAULT_URL");
}

TEST(NetworkGuard, MemqIsAlwaysAllowed) {
  EXPECT_NO_THROW(RequireIsolatedNetworkForUdpm("memq://", "test"));
}

TEST(NetworkGuard, UdpmRefusedExactlyWhenAnotherInterfaceIsVisible) {
  unsetenv("PROBES_ALLOW_HOST_NETWORK");
  if (NonLoopbackInterfaces().empty()) {
    EXPECT_NO_THROW(RequireIsolatedNetworkForUdpm("udpm://239.255.76.67:7667", "test"));
  } else {
    try {
      RequireIsolatedNetworkForUdpm("udpm://239.255.76.67:7667", "test");
      FAIL() << "udpm allowed with interfaces other than lo";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("netns_run.sh"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace probes
