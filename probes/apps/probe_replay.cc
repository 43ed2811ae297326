// probe_replay: the stand-in for the haptic device. Plays a recorded
// trajectory (CSV or LCM log) at real time as probe_pose_t, matches the
// server's wrench_t answers by pose_seq, and reports per-pose results (CSV),
// a JSON summary and a printed summary.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <string>
#include <thread>

#include "haptics_msgs/probe_pose_t.hpp"
#include "probes/transport/channels.h"
#include "probes/trajectory/input_error.h"
#include "probes/trajectory/load_trajectory.h"
#include "probes/transport/mono_clock.h"
#include "probes/transport/network_guard.h"
#include "probes/transport/pose_message.h"
#include "probes/transport/realtime.h"
#include "probes/transport/replay_listener.h"
#include "probes/results/replay_result_csv.h"
#include "probes/results/replay_summary.h"
#include "probes/transport/sender.h"
#include "probes/results/session_plot.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitInput = 1;
constexpr int kExitLcm = 2;
constexpr int kExitCheckFailed = 3;
constexpr int kExitNoServer = 4;

constexpr const char* kFooter = R"(
The trajectory is a CSV (header time,x,y,z,qw,qx,qy,qz; time in s) or an LCM
log (lcm-logger / probe_recorder; only --pose-channel events are used). Each
pose is sent at start + (t - t_first) / rate-scale on CLOCK_MONOTONIC with
seq = first-seq + index and utime = the send time in us. A wrench answers a
pose when its pose_seq, pose_utime and pose_session match; latency = receive
- send time.

Every pose carries this replay's sender identity (--session, random by
default, and --device). The run fails when the server renders another
sender while this replay is sending: a wrench answering another sender's
live stream, or a status naming this session as rejected or another sender
as the pose source (haptic_server locks onto one sender at a time).

A pose left unanswered while a later one was answered is "superseded" (the
server took a newer pose in the same tick, or the datagram was lost on the
way); one with no later answer is "lost". Lost poses always fail; superseded ones beyond --max-superseded.

Exit codes: 0 every pose sent and answered (up to --max-superseded), all
wrenches finite and within --max-force; 1 bad input or options; 2 LCM error; 3 a check failed (the
summary says which); 4 no server message within --start-delay.)";

void SleepSeconds(double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); }

// The trajectory `times` times back to back, each copy starting one sample
// period (the last one's) after the previous copy's last sample (for soak
// runs; the shipped trajectories end where they start).
probes::Trajectory Repeated(const probes::Trajectory& one, int times) {
  const size_t n = one.size();
  const double step = n > 1 ? one[n - 1].t - one[n - 2].t : 1e-3;
  const double period = one.back().t - one.front().t + step;
  probes::Trajectory all;
  all.reserve(n * static_cast<size_t>(times));
  for (int k = 0; k < times; ++k) {
    for (const probes::PoseSample& s : one) {
      all.push_back(s);
      all.back().t += k * period;
    }
  }
  return all;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"probe_replay: plays a probe trajectory to haptic_server and checks the answers"};
  app.footer(kFooter);
  std::string trajectory_path, url, out_csv, summary_json;
  std::string pose_channel = probes::kDefaultPoseChannel;
  std::string wrench_channel = probes::kDefaultWrenchChannel;
  std::string status_channel = probes::kDefaultStatusChannel;
  double rate_scale = 1.0, start_delay = 10.0, grace = 0.5;
  std::optional<double> max_force;
  double max_superseded = 0.0;
  int64_t first_seq = 0;
  bool realtime = false;
  int repeat = 1;
  std::string session_text, device = "probe_replay", log_session_text;

  app.add_option("--trajectory", trajectory_path, "trajectory CSV or LCM log")
      ->required()->check(CLI::ExistingFile);
  app.add_option("--lcm-url", url, "LCM URL (default: LCM's default, udpm)");
  app.add_option("--pose-channel", pose_channel)->capture_default_str();
  app.add_option("--wrench-channel", wrench_channel)->capture_default_str();
  app.add_option("--status-channel", status_channel)->capture_default_str();
  app.add_option("--rate-scale", rate_scale, "playback speed factor (2 = twice as fast)")
      ->capture_default_str()->check(CLI::Range(0.01, 100.0));
  app.add_option("--out", out_csv, "per-pose result CSV");
  app.add_option("--summary", summary_json, "JSON summary");
  std::string plot_png;
  bool no_plot = false;
  app.add_option("--plot", plot_png,
                 "session plot PNG (gnuplot: |force|, |torque|, depth, contacts, round trip over "
                 "time; default with --out: the CSV's path with .png)");
  app.add_flag("--no-plot", no_plot, "do not write the session plot");
  app.add_option("--start-delay", start_delay,
                 "wait up to this long (s) for a first status or wrench message; 0: do not wait")
      ->capture_default_str()->check(CLI::Range(0.0, 600.0));
  app.add_option("--grace", grace, "wait this long (s) after the last pose for late answers")
      ->capture_default_str()->check(CLI::Range(0.0, 60.0));
  app.add_option("--max-force", max_force, "fail if any |force| exceeds this (N)")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-superseded", max_superseded,
                 "tolerate this fraction of poses sent going unanswered because a later pose "
                 "was answered (a newest-pose server drops one when two arrive in a tick)")
      ->capture_default_str()->check(CLI::Range(0.0, 1.0));
  app.add_option("--first-seq", first_seq, "seq of the first pose")->capture_default_str();
  app.add_flag("--realtime", realtime, "ask for SCHED_FIFO for the sending thread");
  app.add_option("--repeat", repeat,
                 "send the trajectory this many times back to back, seq and time continuing "
                 "(soak runs)")
      ->capture_default_str()->check(CLI::Range(1, 100000));
  app.add_option("--session", session_text,
                 "sender session id (0x-prefixed hex or decimal, non-zero; default: random)");
  app.add_option("--device", device, "sender device name")->capture_default_str();
  app.add_option("--log-session", log_session_text,
                 "for an LCM log holding several senders: replay this sender's poses");
  CLI11_PARSE(app, argc, argv);
  if (!plot_png.empty() && out_csv.empty()) {
    std::cerr << "probe_replay: --plot needs --out (the plot is drawn from the result CSV)\n";
    return kExitInput;
  }

  probes::Trajectory trajectory;
  probes::Sender sender;
  try {
    sender = probes::MakeSender(session_text, device);
    int64_t log_session = 0;
    if (!log_session_text.empty() && !haptics_msgs::ParseSession(log_session_text, &log_session))
      throw probes::InputError("--log-session: '" + log_session_text + "' is not a non-zero session id");
    trajectory = probes::LoadTrajectory(trajectory_path, pose_channel, log_session);
    if (repeat > 1) trajectory = Repeated(trajectory, repeat);
    probes::RequireIsolatedNetworkForUdpm(url, "probe_replay");
  } catch (const std::exception& e) {
    std::cerr << "probe_replay: " << e.what() << "\n";
    return kExitInput;
  }

  lcm::LCM lcm(url);
  if (!lcm.good()) {
    std::cerr << "probe_replay: cannot initialise LCM with URL '" << url << "'\n";
    return kExitLcm;
  }
  std::cerr << "probe_replay: sender " << sender.Describe() << "\n";
  probes::SeqMatcher matcher(first_seq, trajectory.size(), sender.session);
  probes::ReplayListener listener(&matcher);
  listener.Subscribe(&lcm, wrench_channel, status_channel);

  // LCM dispatches on this thread; the main thread only publishes.
  std::atomic<bool> stop{false};
  std::thread receiver([&] {
    while (!stop) lcm.handleTimeout(20);
  });
  auto finish_receiver = [&] {
    stop = true;
    receiver.join();
  };

  if (start_delay > 0.0) {
    const int64_t give_up = probes::MonotonicNs() + static_cast<int64_t>(start_delay * 1e9);
    while (!listener.server_seen() && probes::MonotonicNs() < give_up) SleepSeconds(0.005);
    if (!listener.server_seen()) {
      finish_receiver();
      std::cerr << "probe_replay: no message on '" << status_channel << "' or '" << wrench_channel
                << "' within " << start_delay
                << " s: is haptic_server running with the same LCM URL and channels?\n";
      return kExitNoServer;
    }
  }

  // Real-time only while sending (probes/transport/realtime.h).
  std::optional<probes::ScopedRealtime> sending_realtime;
  if (realtime) {
    sending_realtime.emplace(80);
    if (!sending_realtime->granted()) std::cerr << "probe_replay: warning: " << sending_realtime->why() << "\n";
  }
  const int64_t start_ns = probes::MonotonicNs() + 5'000'000;
  const double t_first = trajectory.front().t;
  int64_t worst_late_ns = 0;
  int publish_failures = 0;
  for (size_t i = 0; i < trajectory.size(); ++i) {
    const int64_t deadline =
        start_ns + static_cast<int64_t>((trajectory[i].t - t_first) / rate_scale * 1e9);
    probes::SleepUntilNs(deadline);
    const int64_t now_ns = probes::MonotonicNs();
    worst_late_ns = std::max(worst_late_ns, now_ns - deadline);
    const int64_t seq = first_seq + static_cast<int64_t>(i);
    const int64_t send_us = now_ns / 1000;
    {
      // Marked before publishing so that even an instant answer finds it.
      std::lock_guard<std::mutex> lock(listener.mutex());
      matcher.MarkSent(seq, send_us);
    }
    haptics_msgs::probe_pose_t msg = probes::MakePoseMessage(trajectory[i], seq, send_us, sender);
    if (lcm.publish(pose_channel, &msg) != 0) ++publish_failures;
  }
  sending_realtime.reset();

  // Grace period: stop early once every pose has its answer.
  const int64_t grace_end = probes::MonotonicNs() + static_cast<int64_t>(grace * 1e9);
  while (listener.first_answers() < static_cast<int64_t>(trajectory.size()) &&
         probes::MonotonicNs() < grace_end) {
    SleepSeconds(0.001);
  }
  finish_receiver();

  probes::SummaryLimits limits;
  limits.force_limit_N = max_force;
  limits.max_superseded_fraction = max_superseded;
  probes::ReplaySummary summary = probes::Summarise(matcher.records(),
                                                    static_cast<int64_t>(trajectory.size()), limits);
  summary.trajectory = trajectory_path;
  summary.sender = sender.Describe();
  summary.other_stream_answers = matcher.other_stream_answers();
  summary.other_stream = haptics_msgs::FormatSession(matcher.other_stream_session());
  summary.statuses_rejecting_us = listener.statuses_rejecting_us();
  summary.statuses_other_source = listener.statuses_other_source();
  summary.other_source = listener.other_source();
  summary.repeat_answers = matcher.repeat_answers();
  summary.no_pose_answers = matcher.no_pose_answers();
  summary.foreign_answers = matcher.foreign_answers();
  summary.wrenches_missed = listener.wrenches_missed();
  summary.max_send_lateness_us = 1e-3 * static_cast<double>(worst_late_ns);
  summary.last_status = listener.last_status();

  try {
    if (!out_csv.empty()) {
      std::ofstream out(out_csv);
      if (!out) throw probes::InputError(out_csv + ": cannot open for writing");
      probes::WriteResultCsv(out, trajectory, matcher.records());
      if (!out.flush()) throw probes::InputError(out_csv + ": write failed");
    }
    if (!out_csv.empty() && !no_plot) {
      if (plot_png.empty()) plot_png = probes::SessionPlotPath(out_csv);
      std::string error;
      if (!probes::WriteSessionPlot(out_csv, plot_png, "probe_replay session: " + trajectory_path, &error)) {
        throw probes::InputError("session plot: " + error);
      }
    }
    if (!summary_json.empty()) {
      std::ofstream out(summary_json);
      if (!out) throw probes::InputError(summary_json + ": cannot open for writing");
      out << probes::ToJson(summary).dump(2) << "\n";
      if (!out.flush()) throw probes::InputError(summary_json + ": write failed");
    }
  } catch (const std::exception& e) {
    std::cerr << "probe_replay: " << e.what() << "\n";
    return kExitInput;
  }
  std::cout << probes::FormatSummary(summary);
  if (!out_csv.empty() && !no_plot) std::cout << "session plot: " << plot_png << "\n";
  std::cout << std::flush;
  if (publish_failures > 0) {
    std::cerr << "probe_replay: " << publish_failures << " publish calls failed\n";
    return kExitLcm;
  }
  return summary.ok() ? kExitOk : kExitCheckFailed;
}
