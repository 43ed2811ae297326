// echo_server: the transport-only baseline. Answers every probe_pose_t with a
// zero wrench_t that echoes pose seq, utime and sender session (any sender:
// it has no source lock), with no computation, and
// publishes a server_status_t at 10 Hz. The round trip measured against it is
// the LCM/loopback share of the real server's latency.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <string>

#include "haptics_msgs/probe_pose_t.hpp"
#include "haptics_msgs/server_status_t.hpp"
#include "haptics_msgs/wrench_t.hpp"
#include "probes/transport/channels.h"
#include "probes/transport/mono_clock.h"
#include "probes/transport/network_guard.h"
#include "probes/transport/realtime.h"
#include "probes/transport/stop_signal.h"

namespace {

class Echo {
 public:
  Echo(lcm::LCM* lcm, std::string wrench_channel)
      : lcm_(lcm), wrench_channel_(std::move(wrench_channel)) {}

  // Raw handler: decoding here (not in a typed subscription) lets the echo
  // count undecodable messages instead of LCM silently dropping them. A plain
  // function (subscribeFunction): LCM 1.3.1's member-function subscriptions
  // crash in sanitizer builds.
  static void OnPose(const lcm::ReceiveBuffer* rbuf, const std::string&, Echo* self) {
    self->Answer(rbuf);
  }

  void Answer(const lcm::ReceiveBuffer* rbuf) {
    haptics_msgs::probe_pose_t pose;
    if (pose.decode(rbuf->data, 0, rbuf->data_size) != static_cast<int>(rbuf->data_size)) {
      ++malformed_;
      return;
    }
    ++received_;
    haptics_msgs::wrench_t w{};
    w.seq = answered_;
    w.pose_seq = pose.seq;
    w.pose_utime = pose.utime;
    w.pose_session = pose.sender_session;
    last_session_ = pose.sender_session;
    last_device_ = pose.sender_device;
    w.utime = probes::MonotonicUs();
    if (lcm_->publish(wrench_channel_, &w) == 0) ++answered_;
  }

  int64_t received() const { return received_; }
  int64_t answered() const { return answered_; }
  int64_t malformed() const { return malformed_; }
  // The sender of the last pose answered: the echo has no source lock, its
  // status names whoever it answered last.
  int64_t last_session() const { return last_session_; }
  const std::string& last_device() const { return last_device_; }

 private:
  lcm::LCM* lcm_;
  std::string wrench_channel_;
  int64_t received_ = 0;
  int64_t answered_ = 0;
  int64_t malformed_ = 0;
  int64_t last_session_ = 0;
  std::string last_device_;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"echo_server: answers each probe pose with a zero wrench (transport baseline)"};
  std::string url;
  std::string pose_channel = probes::kDefaultPoseChannel;
  std::string wrench_channel = probes::kDefaultWrenchChannel;
  std::string status_channel = probes::kDefaultStatusChannel;
  double duration = 0.0;
  bool realtime = false;
  app.add_option("--lcm-url", url, "LCM URL (default: LCM's default, udpm)");
  app.add_option("--pose-channel", pose_channel)->capture_default_str();
  app.add_option("--wrench-channel", wrench_channel)->capture_default_str();
  app.add_option("--status-channel", status_channel)->capture_default_str();
  app.add_option("--duration", duration, "stop after this many seconds (0: at SIGINT/SIGTERM)")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  app.add_flag("--realtime", realtime, "ask for SCHED_FIFO");
  CLI11_PARSE(app, argc, argv);

  try {
    probes::RequireIsolatedNetworkForUdpm(url, "echo_server");
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  lcm::LCM lcm(url);
  if (!lcm.good()) {
    std::cerr << "echo_server: cannot initialise LCM with URL '" << url << "'\n";
    return 2;
  }
  if (realtime) {
    std::string why;
    if (!probes::TryRealtime(80, &why)) std::cerr << "echo_server: warning: " << why << "\n";
  }
  probes::InstallStopSignalHandlers();
  Echo echo(&lcm, wrench_channel);
  lcm.subscribeFunction(pose_channel, &Echo::OnPose, &echo);

  const int64_t start_us = probes::MonotonicUs();
  const int64_t end_us = duration > 0.0 ? start_us + static_cast<int64_t>(duration * 1e6) : -1;
  int64_t next_status_us = start_us;
  int64_t status_count = 0;
  while (!probes::g_stop_requested && (end_us < 0 || probes::MonotonicUs() < end_us)) {
    const int64_t now = probes::MonotonicUs();
    if (now >= next_status_us) {
      haptics_msgs::server_status_t st{};
      st.utime = now;
      st.tick_count = echo.answered();
      st.poses_received = echo.received();
      st.messages_malformed = echo.malformed();
      st.source_session = echo.last_session();
      st.source_device = echo.last_device();
      st.source_alive = echo.last_session() != 0;
      lcm.publish(status_channel, &st);
      ++status_count;
      next_status_us += 100'000;
    }
    const int64_t wait_ms = std::max<int64_t>(1, (next_status_us - probes::MonotonicUs()) / 1000);
    // A stop signal interrupts the wait (EINTR): that is not an error.
    if (lcm.handleTimeout(static_cast<int>(wait_ms)) < 0 && !probes::g_stop_requested) {
      std::cerr << "echo_server: LCM handle failed\n";
      return 2;
    }
  }
  std::printf("echo_server: %.2f s, poses received %lld, answered %lld, malformed %lld, "
              "status messages %lld\n",
              1e-6 * static_cast<double>(probes::MonotonicUs() - start_us),
              static_cast<long long>(echo.received()), static_cast<long long>(echo.answered()),
              static_cast<long long>(echo.malformed()), static_cast<long long>(status_count));
  return 0;
}
