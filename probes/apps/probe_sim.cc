// probe_sim: scripted probe motions (approach_and_press, slide, stir,
// insert_peg), published as probe_pose_t at a fixed rate over LCM and/or
// written as a trajectory CSV (the committed trajectories are made this way).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <string>
#include <vector>

#include "haptics_msgs/probe_pose_t.hpp"
#include "probes/transport/channels.h"
#include "probes/trajectory/input_error.h"
#include "probes/transport/mono_clock.h"
#include "probes/trajectory/motion_params.h"
#include "probes/trajectory/motion_scripts.h"
#include "probes/transport/network_guard.h"
#include "probes/transport/pose_message.h"
#include "probes/transport/realtime.h"
#include "probes/transport/sender.h"
#include "probes/trajectory/trajectory_csv.h"

namespace {

constexpr const char* kFooter = R"(
Parameters come from --params FILE (YAML mapping with the option names below
without dashes, e.g. `centre: [0, 0, 0.05]`) and are overridden by options
given on the command line. See probes/trajectory/motion_params.h for what each one means
per script. With --csv-out and without --publish nothing is sent and no time
passes: the trajectory is computed and written at once.

Exit codes: 0 done, 1 bad parameters or I/O error, 2 LCM error.)";

template <size_t N>
void CopyIfGiven(const CLI::Option* opt, const std::vector<double>& from, std::array<double, N>* to) {
  if (opt->count() > 0) std::copy(from.begin(), from.end(), to->begin());
}

int Publish(const probes::Trajectory& trajectory, const std::string& url,
            const std::string& channel, int64_t first_seq, bool realtime, const probes::Sender& sender) {
  probes::RequireIsolatedNetworkForUdpm(url, "probe_sim");
  lcm::LCM lcm(url);
  if (!lcm.good()) {
    std::cerr << "probe_sim: cannot initialise LCM with URL '" << url << "'\n";
    return 2;
  }
  std::optional<probes::ScopedRealtime> sending_realtime;  // while publishing only
  if (realtime) {
    sending_realtime.emplace(80);
    if (!sending_realtime->granted()) std::cerr << "probe_sim: warning: " << sending_realtime->why() << "\n";
  }
  std::fprintf(stderr, "probe_sim: sender %s\n", sender.Describe().c_str());
  // Absolute deadlines from one start time: lateness never accumulates.
  const int64_t start_ns = probes::MonotonicNs() + 5'000'000;
  const double t_first = trajectory.front().t;
  int64_t worst_late_ns = 0;
  for (size_t k = 0; k < trajectory.size(); ++k) {
    const int64_t deadline = start_ns + static_cast<int64_t>((trajectory[k].t - t_first) * 1e9);
    probes::SleepUntilNs(deadline);
    const int64_t now = probes::MonotonicNs();
    worst_late_ns = std::max(worst_late_ns, now - deadline);
    haptics_msgs::probe_pose_t msg =
        probes::MakePoseMessage(trajectory[k], first_seq + static_cast<int64_t>(k), now / 1000, sender);
    if (lcm.publish(channel, &msg) != 0) {
      std::cerr << "probe_sim: publish failed on '" << channel << "' at seq " << msg.seq << "\n";
      return 2;
    }
  }
  std::printf("probe_sim: published %zu poses on %s as %s over %.3f s, worst lateness %.0f us\n",
              trajectory.size(), channel.c_str(), sender.Describe().c_str(), trajectory.back().t - t_first,
              1e-3 * static_cast<double>(worst_late_ns));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"probe_sim: scripted probe motions over LCM or to a trajectory CSV"};
  app.footer(kFooter);
  std::string params_file, csv_out, script;
  std::string url;
  std::string channel = probes::kDefaultPoseChannel;
  std::vector<double> centre, direction, orientation;
  double amplitude = 0, depth = 0, speed = 0, duration = 0, approach = 0, hold = 0, rate = 0;
  int64_t first_seq = 0;
  bool publish = false, realtime = false;
  std::string session_text, device = "probe_sim";

  app.add_option("--params", params_file, "YAML file of motion parameters")->check(CLI::ExistingFile);
  auto* o_script = app.add_option("--script", script, "approach_and_press | slide | stir | insert_peg");
  auto* o_centre = app.add_option("--centre", centre, "reference point x y z (m)")->expected(3);
  auto* o_amp = app.add_option("--amplitude", amplitude, "script-specific extent (m)");
  auto* o_depth = app.add_option("--depth", depth, "how far below centre (m)");
  auto* o_speed = app.add_option("--speed", speed, "average speed of each move (m/s)");
  auto* o_dur = app.add_option("--duration", duration, "total duration (s)");
  auto* o_appr = app.add_option("--approach", approach, "start height above centre (m)");
  auto* o_hold = app.add_option("--hold", hold, "pause at the ends of each cycle (s)");
  auto* o_dir = app.add_option("--direction", direction, "slide direction x y z")->expected(3);
  auto* o_ori = app.add_option("--orientation", orientation, "R_WP as w x y z")->expected(4);
  auto* o_rate = app.add_option("--rate", rate, "sample rate (Hz), default 1000");
  app.add_option("--csv-out", csv_out, "write the trajectory CSV here");
  app.add_flag("--publish", publish, "publish over LCM even when --csv-out is given");
  app.add_option("--lcm-url", url, "LCM URL (default: LCM's default, udpm)");
  app.add_option("--pose-channel", channel, "channel for probe_pose_t")->capture_default_str();
  app.add_option("--first-seq", first_seq, "seq of the first pose")->capture_default_str();
  app.add_flag("--realtime", realtime, "ask for SCHED_FIFO while publishing");
  app.add_option("--session", session_text,
                 "sender session id (0x-prefixed hex or decimal, non-zero; default: random)");
  app.add_option("--device", device, "sender device name")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  probes::MotionParams params;
  try {
    if (!params_file.empty()) probes::LoadMotionParamsYaml(params_file, &params);
    if (o_script->count() > 0) params.script = script;
    CopyIfGiven(o_centre, centre, &params.centre);
    if (o_amp->count() > 0) params.amplitude = amplitude;
    if (o_depth->count() > 0) params.depth = depth;
    if (o_speed->count() > 0) params.speed = speed;
    if (o_dur->count() > 0) params.duration = duration;
    if (o_appr->count() > 0) params.approach = approach;
    if (o_hold->count() > 0) params.hold = hold;
    CopyIfGiven(o_dir, direction, &params.direction);
    CopyIfGiven(o_ori, orientation, &params.orientation);
    if (o_rate->count() > 0) params.rate_hz = rate;
    probes::ValidateMotionParams(&params);
    const probes::Trajectory trajectory = probes::SampleMotion(params);
    if (trajectory.size() < 2) throw probes::InputError("duration * rate gives fewer than 2 samples");

    if (!csv_out.empty()) {
      std::ofstream out(csv_out);
      if (!out) throw probes::InputError(csv_out + ": cannot open for writing");
      probes::WriteTrajectoryCsv(out, trajectory);
      if (!out.flush()) throw probes::InputError(csv_out + ": write failed");
      std::printf("probe_sim: wrote %zu samples (%s, %.3f s at %.0f Hz) to %s\n", trajectory.size(),
                  params.script.c_str(), trajectory.back().t, params.rate_hz, csv_out.c_str());
    }
    const probes::Sender sender = probes::MakeSender(session_text, device);
    if (csv_out.empty() || publish) return Publish(trajectory, url, channel, first_seq, realtime, sender);
    return 0;
  } catch (const probes::InputError& e) {
    std::cerr << "probe_sim: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "probe_sim: " << e.what() << "\n";
    return 2;
  }
}
