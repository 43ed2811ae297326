// bad_input_sender: sends malformed traffic to the pose channel while a
// replay runs, to check that the server keeps answering. Per round:
//   1. a raw UDP datagram of random bytes (not LCM framing at all),
//   2. an LCM-framed datagram on the channel with a random payload,
//   3. an LCM-framed probe_pose_t cut short (right fingerprint, truncated),
//   4. a well-formed message of the wrong type (wrench_t) on the channel.
// 2-4 reach the server's pose subscription and cannot be decoded as
// probe_pose_t. Refuses to send unless only loopback is visible.
#include <CLI/CLI.hpp>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "haptics_msgs/probe_pose_t.hpp"
#include "haptics_msgs/wrench_t.hpp"
#include "probes/transport/network_guard.h"

namespace {

constexpr uint32_t kLcmShortMagic = 0x4c433032;  // "LC02": unfragmented LCM datagram

struct Group {
  std::string address = "239.255.76.67";  // LCM's default udpm group and port
  int port = 7667;
};

// Parses "udpm://ADDR:PORT?options"; an empty URL means $LCM_DEFAULT_URL or LCM's default.
Group ParseUdpmUrl(std::string url) {
  if (url.empty() && std::getenv("LCM_DEFAULT_URL") != nullptr) url = std::getenv("LCM_DEFAULT_URL");
  Group g;
  if (url.empty()) return g;
  const std::string prefix = "udpm://";
  if (url.rfind(prefix, 0) != 0) throw std::runtime_error("not a udpm:// URL: '" + url + "'");
  std::string rest = url.substr(prefix.size());
  rest = rest.substr(0, rest.find('?'));
  const size_t colon = rest.find(':');
  if (!rest.empty()) g.address = rest.substr(0, colon);
  if (colon != std::string::npos) g.port = std::stoi(rest.substr(colon + 1));
  return g;
}

std::vector<uint8_t> Framed(uint32_t seq, const std::string& channel, const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> d;
  for (uint32_t word : {kLcmShortMagic, seq}) {
    for (int shift = 24; shift >= 0; shift -= 8) d.push_back(static_cast<uint8_t>(word >> shift));
  }
  d.insert(d.end(), channel.begin(), channel.end());
  d.push_back(0);
  d.insert(d.end(), payload.begin(), payload.end());
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bad_input_sender: malformed traffic on the pose channel (namespace only)"};
  std::string url, channel = "PROBE_POSE";
  int rounds = 200;
  double interval_ms = 10.0, start_delay_s = 0.0;
  app.add_option("--lcm-url", url, "udpm URL of the bus (default: LCM's default)");
  app.add_option("--channel", channel)->capture_default_str();
  app.add_option("--rounds", rounds, "rounds of the four bad messages")->capture_default_str();
  app.add_option("--interval-ms", interval_ms, "pause between rounds")->capture_default_str();
  app.add_option("--start-delay", start_delay_s, "wait this long (s) before the first round");
  CLI11_PARSE(app, argc, argv);

  Group group;
  try {
    probes::RequireIsolatedNetworkForUdpm(url, "bad_input_sender");
    if (probes::LcmProvider(url) != "udpm") throw std::runtime_error("needs a udpm:// bus");
    group = ParseUdpmUrl(url);
  } catch (const std::exception& e) {
    std::cerr << "bad_input_sender: " << e.what() << "\n";
    return 1;
  }
  lcm::LCM lcm(url);
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (!lcm.good() || fd < 0) {
    std::cerr << "bad_input_sender: cannot open LCM or a UDP socket\n";
    return 2;
  }
  const unsigned char ttl = 0, loop = 1;  // never routed off the host, delivered locally
  setsockopt(fd, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof(ttl));
  setsockopt(fd, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof(loop));
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<uint16_t>(group.port));
  if (inet_pton(AF_INET, group.address.c_str(), &to.sin_addr) != 1) {
    std::cerr << "bad_input_sender: bad group address '" << group.address << "'\n";
    return 1;
  }
  auto send = [&](const std::vector<uint8_t>& d) {
    return sendto(fd, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof(to)) ==
           static_cast<ssize_t>(d.size());
  };

  std::this_thread::sleep_for(std::chrono::duration<double>(start_delay_s));
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> byte(0, 255);
  auto random_bytes = [&](size_t n) {
    std::vector<uint8_t> v(n);
    for (auto& b : v) b = static_cast<uint8_t>(byte(rng));
    return v;
  };
  haptics_msgs::probe_pose_t pose{};
  pose.orientation[0] = 1.0;
  std::vector<uint8_t> pose_bytes(pose.getEncodedSize());
  pose.encode(pose_bytes.data(), 0, static_cast<int>(pose_bytes.size()));
  pose_bytes.resize(pose_bytes.size() / 2);

  long raw = 0, framed = 0, truncated = 0, wrong_type = 0, failures = 0;
  uint32_t lcm_seq = 0x70000000;  // far from the LCM instances' own sequence numbers
  for (int r = 0; r < rounds; ++r) {
    std::vector<uint8_t> junk = random_bytes(1 + rng() % 1400);
    junk[0] = 0x00;  // can never start with an LCM magic number
    send(junk) ? ++raw : ++failures;
    send(Framed(lcm_seq++, channel, random_bytes(1 + rng() % 200))) ? ++framed : ++failures;
    send(Framed(lcm_seq++, channel, pose_bytes)) ? ++truncated : ++failures;
    haptics_msgs::wrench_t w{};
    w.pose_seq = -12345;
    lcm.publish(channel, &w) == 0 ? ++wrong_type : ++failures;
    std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(interval_ms));
  }
  close(fd);
  std::printf("bad_input_sender: raw %ld, framed garbage %ld, truncated poses %ld, wrong type %ld, "
              "send failures %ld; undecodable_on_channel=%ld\n",
              raw, framed, truncated, wrong_type, failures, framed + truncated + wrong_type);
  return failures == 0 ? 0 : 2;
}
