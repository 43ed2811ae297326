// probe_recorder: records the pose, wrench and status channels (or every
// channel) to an LCM log file for a duration. `lcm-logger` does the same
// job; this tool exists so that scripts need nothing beyond the build and so
// that the channel set defaults to the server's. It also tells who sent the
// poses: the summary lists each sender (probe_pose_t session and device) on
// the pose channel, so a log that mixes two devices is visible at once.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "haptics_msgs/probe_pose_t.hpp"
#include "haptics_msgs/probe_pose_v1_t.hpp"
#include "msgs/sender_identity.h"
#include "probes/transport/channels.h"
#include "probes/transport/mono_clock.h"
#include "probes/transport/network_guard.h"
#include "probes/transport/stop_signal.h"

namespace {

class Recorder {
 public:
  Recorder(lcm::LogFile* log, std::string pose_channel) : log_(log), pose_channel_(std::move(pose_channel)) {}

  // A plain function (subscribeFunction): LCM 1.3.1's member-function
  // subscriptions crash in sanitizer builds.
  static void OnMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel, Recorder* self) {
    self->Write(rbuf, channel);
  }

  void Write(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    lcm::LogEvent event{};
    event.eventnum = events_;
    event.timestamp = rbuf->recv_utime;  // wall clock (µs since epoch), as lcm-logger writes
    event.channel = channel;
    event.datalen = static_cast<int32_t>(rbuf->data_size);
    event.data = rbuf->data;
    if (log_->writeEvent(&event) != 0) {
      ++write_errors_;
      return;
    }
    ++events_;
    ++per_channel_[channel];
    if (channel == pose_channel_) CountSender(rbuf);
  }

  // "0x... 'device' N" per sender of the pose channel, in order of appearance.
  std::string Senders() const {
    std::string out;
    for (const auto& [who, n] : senders_) out += (out.empty() ? "" : ", ") + who + " " + std::to_string(n);
    if (old_version_ > 0) out += (out.empty() ? "" : ", ") + std::string("version 1 (no sender) ") + std::to_string(old_version_);
    return out.empty() ? "none" : out;
  }

  void CountSender(const lcm::ReceiveBuffer* rbuf) {
    const int size = static_cast<int>(rbuf->data_size);
    haptics_msgs::probe_pose_t pose;
    if (pose.decode(rbuf->data, 0, size) != size) {
      haptics_msgs::probe_pose_v1_t v1;
      if (v1.decode(rbuf->data, 0, size) == size) ++old_version_;
      return;
    }
    const std::string who = haptics_msgs::FormatSession(pose.sender_session) + " '" + pose.sender_device + "'";
    for (auto& [known, n] : senders_) {
      if (known == who) {
        ++n;
        return;
      }
    }
    senders_.emplace_back(who, 1);
  }

  int64_t events() const { return events_; }
  int64_t write_errors() const { return write_errors_; }
  const std::map<std::string, int64_t>& per_channel() const { return per_channel_; }

 private:
  lcm::LogFile* log_;
  int64_t events_ = 0;
  int64_t write_errors_ = 0;
  std::map<std::string, int64_t> per_channel_;
  std::string pose_channel_;
  std::vector<std::pair<std::string, int64_t>> senders_;  // few: a linear search
  int64_t old_version_ = 0;
};

// LCM channel subscriptions are POSIX regular expressions: escape names so
// that they match literally.
std::string EscapeRegex(const std::string& name) {
  std::string out;
  for (char c : name) {
    if (std::string("\\^$.|?*+()[]{}").find(c) != std::string::npos) out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"probe_recorder: records haptic channels to an LCM log file (like lcm-logger)"};
  std::string out_path, url;
  std::vector<std::string> channels = {probes::kDefaultPoseChannel, probes::kDefaultWrenchChannel,
                                       probes::kDefaultStatusChannel};
  double duration = 0.0;
  bool all = false;
  std::string pose_channel = probes::kDefaultPoseChannel;
  app.add_option("--out", out_path, "LCM log file to write")->required();
  app.add_option("--lcm-url", url, "LCM URL (default: LCM's default, udpm)");
  app.add_option("--channels", channels, "channels to record")->capture_default_str();
  app.add_flag("--all-channels", all, "record every channel instead");
  app.add_option("--duration", duration, "stop after this many seconds (0: at SIGINT/SIGTERM)")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  app.add_option("--pose-channel", pose_channel, "channel whose probe_pose_t senders are listed")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  try {
    probes::RequireIsolatedNetworkForUdpm(url, "probe_recorder");
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  lcm::LogFile log(out_path, "w");
  if (!log.good()) {
    std::cerr << "probe_recorder: " << out_path << ": cannot open for writing\n";
    return 1;
  }
  lcm::LCM lcm(url);
  if (!lcm.good()) {
    std::cerr << "probe_recorder: cannot initialise LCM with URL '" << url << "'\n";
    return 2;
  }
  probes::InstallStopSignalHandlers();
  Recorder recorder(&log, pose_channel);
  if (all) {
    lcm.subscribeFunction(".*", &Recorder::OnMessage, &recorder);
  } else {
    for (const std::string& c : channels) {
      lcm.subscribeFunction(EscapeRegex(c), &Recorder::OnMessage, &recorder);
    }
  }
  // Ready line on stderr: scripts wait for it before starting the sender.
  std::cerr << "probe_recorder: recording to " << out_path << "\n";

  const int64_t start_us = probes::MonotonicUs();
  const int64_t end_us = duration > 0.0 ? start_us + static_cast<int64_t>(duration * 1e6) : -1;
  while (!probes::g_stop_requested && (end_us < 0 || probes::MonotonicUs() < end_us)) {
    // A stop signal interrupts the wait (EINTR): that is not an error.
    if (lcm.handleTimeout(50) < 0 && !probes::g_stop_requested) {
      std::cerr << "probe_recorder: LCM handle failed\n";
      return 2;
    }
  }
  std::printf("probe_recorder: %lld events in %.2f s to %s", static_cast<long long>(recorder.events()),
              1e-6 * static_cast<double>(probes::MonotonicUs() - start_us), out_path.c_str());
  for (const auto& [channel, n] : recorder.per_channel()) {
    std::printf("; %s %lld", channel.c_str(), static_cast<long long>(n));
  }
  std::printf("; pose senders: %s\n", recorder.Senders().c_str());
  if (recorder.write_errors() > 0) {
    std::cerr << "probe_recorder: " << recorder.write_errors() << " events could not be written\n";
    return 1;
  }
  return 0;
}
