// The smallest haptic client: it plays a scripted motion as probe_pose_t at
// 1 kHz on PROBE_POSE and prints the wrench_t answers from HAPTIC_WRENCH.
// The motion suits config/box_on_box.yaml: the 2 cm box tool hovers 5 mm
// above the table for 1.2 s (the server ramps its force in over the first
// second), presses 5 mm into it, holds, and lifts off again.
//   probe_client [LCM_URL]     (udpm: run it inside scripts/netns_run.sh)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <sys/select.h>

#include <lcm/lcm-cpp.hpp>

#include "haptics_msgs/probe_pose_t.hpp"
#include "haptics_msgs/sender_identity.h"
#include "haptics_msgs/wrench_t.hpp"

using Clock = std::chrono::steady_clock;  // CLOCK_MONOTONIC, like the server

int64_t NowUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(Clock::now().time_since_epoch())
      .count();
}

// Tool height (m) at time t (s): z = 0.01 is the box tool resting on the table.
double ScriptedZ(double t) {
  const double hover = 0.015, pressed = 0.005;
  if (t < 1.2) return hover;
  if (t < 2.2) return hover + (pressed - hover) * 0.5 * (1 - std::cos(M_PI * (t - 1.2)));
  if (t < 2.7) return pressed;
  if (t < 3.7) return pressed + (hover - pressed) * 0.5 * (1 - std::cos(M_PI * (t - 2.7)));
  return hover;
}

// Dispatches answers as they arrive until `until` (select: microsecond timeout).
void HandleUntil(lcm::LCM& lcm, Clock::time_point until) {
  for (auto now = Clock::now(); now < until; now = Clock::now()) {
    timeval tv{0, std::chrono::duration_cast<std::chrono::microseconds>(until - now).count()};
    fd_set fds;
    FD_ZERO(&fds);
    FD_SET(lcm.getFileno(), &fds);
    if (select(lcm.getFileno() + 1, &fds, nullptr, nullptr, &tv) > 0) lcm.handle();
  }
}

struct WrenchPrinter {
  int64_t session = 0;  // ours: answers rendering another sender's stream are not ours
  bool server_seen = false;
  int answers = 0;  // poses answered (the server repeats its last answer when no new pose came)
  // Poses overtaken by a newer one before the server's tick took them: a
  // sender that bursts (a late process catching up) gets its newest pose
  // rendered, never a queue of old ones. Counted from gaps in pose_seq.
  int superseded = 0;
  int64_t last_seq = -1;
  double max_force = 0;
  // A plain function with a context (subscribeFunction), not a member
  // function: LCM 1.3.1's member-function subscriptions crash in builds with
  // -fsanitize=vptr (the handler is called with a null subscription).
  static void OnWrench(const lcm::ReceiveBuffer*, const std::string&,
                       const haptics_msgs::wrench_t* w, WrenchPrinter* self) {
    self->Print(w);
  }
  void Print(const haptics_msgs::wrench_t* w) {
    server_seen = true;
    if (w->pose_session != session) return;  // not rendering our stream (yet)
    if (w->pose_seq < 0 || w->pose_seq <= last_seq) return;  // no pose yet, or a repeat
    superseded += static_cast<int>(w->pose_seq - last_seq - 1);
    last_seq = w->pose_seq;
    ++answers;
    const double f = std::sqrt(w->force[0] * w->force[0] + w->force[1] * w->force[1] +
                               w->force[2] * w->force[2]);
    max_force = std::max(max_force, f);
    if (w->pose_seq % 100 != 0) return;  // print one answer in 100
    std::printf("pose %lld  force %.3f %.3f %.3f N  torque %.4f %.4f %.4f N·m  depth %.2f mm  "
                "contacts %d  round_trip %lld us\n",
                static_cast<long long>(w->pose_seq), w->force[0], w->force[1], w->force[2],
                w->torque[0], w->torque[1], w->torque[2], 1e3 * w->penetration_depth,
                w->contact_count, static_cast<long long>(NowUs() - w->pose_utime));
  }
};

int main(int argc, char** argv) {
  lcm::LCM lcm(argc > 1 ? argv[1] : "");
  if (!lcm.good()) {
    std::fprintf(stderr, "probe_client: cannot open LCM\n");
    return 1;
  }
  WrenchPrinter printer;
  // Who we are: the server renders one sender at a time (msgs/README.md).
  printer.session = haptics_msgs::NewSession();
  lcm.subscribeFunction("HAPTIC_WRENCH", &WrenchPrinter::OnWrench, &printer);

  // The server publishes at 1 kHz from its start, posed or not: wait for it.
  const auto give_up = Clock::now() + std::chrono::seconds(10);
  while (!printer.server_seen && Clock::now() < give_up) lcm.handleTimeout(100);
  if (!printer.server_seen) {
    std::fprintf(stderr, "probe_client: no wrench on HAPTIC_WRENCH within 10 s: is haptic_server running?\n");
    return 2;
  }

  const int n = 4000;  // 4 s at 1 kHz
  const auto start = Clock::now();
  for (int i = 0; i < n; ++i) {
    haptics_msgs::probe_pose_t pose{};
    pose.version = haptics_msgs::probe_pose_t::VERSION;
    pose.sender_session = printer.session;
    pose.sender_device = "probe_client";
    pose.utime = NowUs();
    pose.seq = i;
    pose.position[2] = ScriptedZ(1e-3 * i);  // x = y = 0, m
    pose.orientation[0] = 1.0;                // identity quaternion (w, x, y, z)
    pose.has_velocity = false;                // the server differentiates the poses
    lcm.publish("PROBE_POSE", &pose);
    HandleUntil(lcm, start + std::chrono::milliseconds(i + 1));  // answers, until the next pose
  }
  HandleUntil(lcm, Clock::now() + std::chrono::milliseconds(200));  // late answers

  std::printf("sent %d poses, %d answered, %d superseded by newer poses, max |force| %.3f N\n", n,
              printer.answers, printer.superseded, printer.max_force);
  return printer.answers > 0 ? 0 : 3;
}
