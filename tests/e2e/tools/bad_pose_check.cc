// bad_pose_check: drives a running haptic_server (box_on_box scene) over LCM
// with well-formed but bad pose traffic and checks that it keeps rendering:
//   1. good poses at 1 kHz, the tool pressed onto the table (reference);
//   2. bad values among them: NaN and inf positions, NaN velocity, zero and
//      non-unit quaternions, positions far outside the workspace;
//   3. order anomalies: duplicate seq, skipped seq, utime going back;
//   4. a burst at 10x the normal rate;
//   5. malformed messages: truncated poses, another LCM type (wrench_t),
//      random payloads on the pose channel;
//   6. good poses again.
// Throughout, every wrench must be finite and within the device limits and
// wrenches must keep coming at >= 80 % of the servo rate. At the end the
// server's status must count each kind of abuse. Prints one line per phase
// and the counters; exits 0 on PASS, 1 on FAIL. Refuses udpm unless only
// loopback is visible (run it through scripts/netns_run.sh).
#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "haptics_msgs/probe_pose_t.hpp"
#include "haptics_msgs/server_status_t.hpp"
#include "haptics_msgs/wrench_t.hpp"
#include "msgs/sender_identity.h"
#include "probes/transport/network_guard.h"

namespace {

using Clock = std::chrono::steady_clock;
using haptics_msgs::probe_pose_t;

struct Limits {
  double max_force = 12.0, max_torque = 0.2;
};

// Wrenches and status from the server, gathered on a receive thread.
class Watcher {
 public:
  explicit Watcher(Limits limits) : limits_(limits) {}
  void OnWrench(const haptics_msgs::wrench_t& w) {
    std::lock_guard<std::mutex> lock(mu_);
    ++wrenches_;
    bool finite = std::isfinite(w.penetration_depth);
    double f2 = 0, t2 = 0;
    for (int i = 0; i < 3; ++i) {
      finite = finite && std::isfinite(w.force[i]) && std::isfinite(w.torque[i]);
      f2 += w.force[i] * w.force[i];
      t2 += w.torque[i] * w.torque[i];
    }
    if (!finite) ++nonfinite_;
    if (std::sqrt(f2) > limits_.max_force * (1 + 1e-9) || std::sqrt(t2) > limits_.max_torque * (1 + 1e-9))
      ++over_limit_;
    last_force_z_ = w.force[2];
  }
  void OnStatus(const haptics_msgs::server_status_t& s) {
    std::lock_guard<std::mutex> lock(mu_);
    status_ = s;
    ++statuses_;
  }
  struct Snapshot {
    long wrenches = 0, nonfinite = 0, over_limit = 0, statuses = 0;
    double last_force_z = 0;
    haptics_msgs::server_status_t status{};
  };
  Snapshot Get() {
    std::lock_guard<std::mutex> lock(mu_);
    return {wrenches_, nonfinite_, over_limit_, statuses_, last_force_z_, status_};
  }

 private:
  Limits limits_;
  std::mutex mu_;
  long wrenches_ = 0, nonfinite_ = 0, over_limit_ = 0, statuses_ = 0;
  double last_force_z_ = 0;
  haptics_msgs::server_status_t status_{};
};

void WrenchHandler(const lcm::ReceiveBuffer*, const std::string&, const haptics_msgs::wrench_t* m, Watcher* w) {
  w->OnWrench(*m);
}
void StatusHandler(const lcm::ReceiveBuffer*, const std::string&, const haptics_msgs::server_status_t* m,
                   Watcher* w) {
  w->OnStatus(*m);
}

int64_t NowMicros() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000 + ts.tv_nsec / 1000;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bad_pose_check: bad pose traffic against a running haptic_server (namespace only)"};
  std::string url, pose_channel = "PROBE_POSE", wrench_channel = "HAPTIC_WRENCH",
                   status_channel = "HAPTIC_STATUS";
  double phase_s = 1.0, wait_s = 20.0, press_z = 0.006;
  Limits limits;
  app.add_option("--lcm-url", url, "LCM URL (default: LCM's default)");
  app.add_option("--phase-seconds", phase_s, "length of each phase (s)")->capture_default_str();
  bool allow_watchdog = false;
  app.add_flag("--allow-watchdog-trips", allow_watchdog,
               "do not fail on watchdog trips (sanitizer builds: the loop is too slow for real time)");
  app.add_option("--wait-server", wait_s, "wait this long (s) for the server's first status")->capture_default_str();
  app.add_option("--press-z", press_z, "handle height while pressing (m)")->capture_default_str();
  app.add_option("--max-force", limits.max_force, "device force limit (N)")->capture_default_str();
  app.add_option("--max-torque", limits.max_torque, "device torque limit (N·m)")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    probes::RequireIsolatedNetworkForUdpm(url, "bad_pose_check");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bad_pose_check: %s\n", e.what());
    return 2;
  }
  lcm::LCM tx(url), rx(url);
  if (!tx.good() || !rx.good()) {
    std::fprintf(stderr, "bad_pose_check: cannot open LCM '%s'\n", url.c_str());
    return 2;
  }
  Watcher watcher(limits);
  rx.subscribeFunction(wrench_channel, &WrenchHandler, &watcher);
  rx.subscribeFunction(status_channel, &StatusHandler, &watcher);
  std::atomic<bool> stop{false};
  std::thread receiver([&] {
    while (!stop) rx.handleTimeout(20);
  });
  auto finish = [&](int code) {
    stop = true;
    receiver.join();
    return code;
  };

  const Clock::time_point wait_until =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(wait_s));
  while (watcher.Get().statuses == 0 && Clock::now() < wait_until)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (watcher.Get().statuses == 0) {
    std::printf("bad_pose_check: FAIL: no status from the server within %.0f s\n", wait_s);
    return finish(1);
  }

  int64_t seq = 0;
  probe_pose_t pose{};
  pose.orientation[0] = 1.0;
  const int64_t session = haptics_msgs::NewSession();
  auto good = [&](double z) {
    pose = probe_pose_t{};
    pose.version = probe_pose_t::VERSION;
    pose.sender_session = session;
    pose.sender_device = "bad_pose_check";
    pose.seq = ++seq;
    pose.utime = NowMicros();
    pose.position[0] = 0.002;
    pose.position[1] = -0.001;
    pose.position[2] = z;
    pose.orientation[0] = 1.0;
    return pose;
  };
  std::vector<uint8_t> bytes;
  auto publish = [&](const probe_pose_t& m) { tx.publish(pose_channel, &m); };
  auto publish_raw = [&](const std::vector<uint8_t>& b) {
    tx.publish(pose_channel, b.data(), static_cast<unsigned>(b.size()));
  };

  struct PhaseResult {
    std::string name;
    long wrenches = 0;
    double seconds = 0;
  };
  std::vector<PhaseResult> phases;
  int failures = 0;
  // Runs `step(i)` every `period` for phase_s, then checks the wrench flow.
  auto phase = [&](const std::string& name, double period_s, const std::function<void(int)>& step) {
    const long before = watcher.Get().wrenches;
    const Clock::time_point start = Clock::now();
    const int steps = static_cast<int>(std::lround(phase_s / period_s));
    for (int i = 0; i < steps; ++i) {
      step(i);
      std::this_thread::sleep_until(
          start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>((i + 1) * period_s)));
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const Watcher::Snapshot s = watcher.Get();
    const long got = s.wrenches - before;
    const double rate = got / seconds;
    const bool ok = rate >= 0.8 * s.status.target_rate_hz;
    std::printf("bad_pose_check: %-12s %.2f s, %ld wrenches (%.0f/s), last f_z %.2f N%s\n", name.c_str(),
                seconds, got, rate, s.last_force_z, ok ? "" : "  <- FAIL: wrenches stopped coming");
    failures += !ok;
  };

  // 1. Reference: approach and press.
  phase("good", 1e-3, [&](int i) { publish(good(0.03 - (0.03 - press_z) * std::min(1.0, i / 500.0))); });
  const Watcher::Snapshot base = watcher.Get();
  if (base.last_force_z < 0.5) {
    std::printf("bad_pose_check: FAIL: not pressing on the table (f_z %.2f N)\n", base.last_force_z);
    ++failures;
  }

  // 2. Bad values: every 10 ms one bad pose, then 2 ms of silence so the
  // loop validates it rather than a newer good one.
  long bad_values = 0;
  phase("bad values", 1e-3, [&](int i) {
    const int k = i % 10;
    if (k == 8 || k == 9) return;
    probe_pose_t m = good(press_z);
    if (k == 7) {
      switch ((i / 10) % 7) {
        case 0: m.position[0] = NAN; break;
        case 1: m.position[2] = INFINITY; break;
        case 2: m.orientation[0] = 0.0; break;  // zero quaternion
        case 3: m.orientation[0] = 0.5; break;  // non-unit
        case 4: m.position[0] = 5.0; break;     // far outside the workspace
        case 5: m.position[1] = -1e300; break;
        case 6: m.has_velocity = 1; m.linear_velocity[2] = NAN; break;
      }
      ++bad_values;
    }
    publish(m);
  });

  // 3. Order anomalies among good poses (same place, so rendering is unchanged).
  long dup = 0, skipped = 0, back = 0;
  phase("order", 1e-3, [&](int i) {
    probe_pose_t m = good(press_z);
    if (i % 20 == 5) {
      m.seq = --seq;  // duplicate of the previous seq
      ++dup;
    } else if (i % 20 == 10) {
      seq += 3;  // three seq numbers never sent
      m.seq = seq;
      skipped += 3;
    } else if (i % 20 == 15) {
      m.utime -= 5000;  // the sender's clock goes back 5 ms
      ++back;
    }
    publish(m);
  });

  // 4. A burst at 10 kHz.
  const long dropped_before = watcher.Get().status.poses_dropped;
  phase("10x burst", 1e-4, [&](int) { publish(good(press_z)); });

  // 5. Malformed messages on the pose channel, between good poses.
  long malformed = 0;
  std::mt19937 rng(7);
  phase("malformed", 1e-3, [&](int i) {
    publish(good(press_z));
    if (i % 5 != 2) return;
    switch ((i / 5) % 3) {
      case 0: {
        probe_pose_t m = good(press_z);
        bytes.assign(m.getEncodedSize(), 0);
        m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
        bytes.resize(bytes.size() - 1 - rng() % 100);  // truncated
        --seq;
        break;
      }
      case 1: {
        haptics_msgs::wrench_t w{};
        bytes.assign(w.getEncodedSize(), 0);
        w.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
        break;
      }
      case 2:
        bytes.resize(1 + rng() % 300);
        for (auto& b : bytes) b = static_cast<uint8_t>(rng());
        break;
    }
    publish_raw(bytes);
    ++malformed;
  });

  // 6. Good again, still sending while waiting for two more status messages.
  phase("good again", 1e-3, [&](int) { publish(good(press_z)); });
  const long statuses = watcher.Get().statuses;
  const Clock::time_point status_until = Clock::now() + std::chrono::seconds(2);
  while (watcher.Get().statuses < statuses + 2 && Clock::now() < status_until) {
    publish(good(press_z));
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  const Watcher::Snapshot end = watcher.Get();
  const haptics_msgs::server_status_t& st = end.status;
  std::printf("bad_pose_check: sent bad values %ld, duplicates %ld, skipped %ld, time back %ld, malformed %ld\n",
              bad_values, dup, skipped, back, malformed);
  std::printf("bad_pose_check: status poses_received=%lld poses_rejected=%lld poses_dropped=%lld "
              "messages_malformed=%lld poses_out_of_order=%lld pose_seq_skipped=%lld pose_time_backwards=%lld "
              "watchdog_trips=%lld deadline_misses=%lld\n",
              (long long)st.poses_received, (long long)st.poses_rejected, (long long)st.poses_dropped,
              (long long)st.messages_malformed, (long long)st.poses_out_of_order,
              (long long)st.pose_seq_skipped, (long long)st.pose_time_backwards, (long long)st.watchdog_trips,
              (long long)st.deadline_misses);
  std::printf("bad_pose_check: wrenches %ld, non-finite %ld, over the device limits %ld, final f_z %.2f N\n",
              end.wrenches, end.nonfinite, end.over_limit, end.last_force_z);

  auto require = [&](bool ok, const std::string& what) {
    if (!ok) {
      std::printf("bad_pose_check: FAIL: %s\n", what.c_str());
      ++failures;
    }
  };
  require(end.nonfinite == 0, "non-finite wrenches");
  require(end.over_limit == 0, "wrenches over the device limits");
  // A bad pose can be superseded by a good one before a tick looks at it
  // (then it is counted as dropped instead): at least half must be rejected.
  require(st.poses_rejected >= bad_values / 2, "poses_rejected does not count the bad values");
  require(st.poses_out_of_order >= dup, "poses_out_of_order does not count the duplicates");
  require(st.pose_seq_skipped >= skipped, "pose_seq_skipped does not count the skipped seq");
  require(st.pose_time_backwards >= back, "pose_time_backwards does not count the clock going back");
  require(st.poses_dropped - dropped_before >= 1000, "the 10x burst did not supersede poses");
  require(st.messages_malformed >= malformed, "messages_malformed does not count the malformed messages");
  require(allow_watchdog || st.watchdog_trips == 0, "the watchdog tripped although good poses kept coming");
  require(end.last_force_z > 0.5, "no longer pressing on the table at the end");
  std::printf("bad_pose_check: %s\n", failures == 0 ? "PASS" : "FAIL");
  return finish(failures == 0 ? 0 : 1);
}
