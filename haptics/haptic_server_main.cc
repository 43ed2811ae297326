// haptic_server: 6-DOF haptic rendering over LCM.
//
//   haptic_server --config FILE [--lcm-url URL] [--cache-dir DIR] [--duration S] [--check]
//                 [--timing-log FILE [--timing-log-ticks N]]
//                 [--accept-session ID] [--accept-device NAME]
//
// Receives probe poses (haptics_msgs::probe_pose_t) on the pose channel,
// renders contact with the scene through a virtual coupling at the servo
// rate, publishes haptics_msgs::wrench_t on the wrench channel every tick and
// haptics_msgs::server_status_t on the status channel at ~10 Hz. Channels,
// rate and gains come from the config file (see config/box_on_box.yaml).
// Logs go to stderr; at exit one summary line goes to stdout.
// One device, one stream (haptics/io/pose_source_lock.h): the server renders the
// first sender (probe_pose_t.sender_session + sender_device) whose pose is
// valid and rejects every other sender while that stream is alive; when it
// has been silent for the watchdog timeout plus the ramp, the next valid
// sender takes over. --accept-session / --accept-device (or lcm.accept_session
// / lcm.accept_device in the config) admit only that sender.
// --timing-log writes one CSV row per tick (period, compute time, contacts,
// flags, deadline miss) after the loop stops, from a buffer of N records
// allocated at start-up (haptics::TickLog): no allocation or file I/O in the
// loop; ticks past N are counted in the file's first line, not stored.
//
// Exit codes: 0 clean stop (SIGINT, SIGTERM or --duration), 1 configuration
// error (message on stderr names the file, key and allowed range; also a bad
// command line or an LCM URL that cannot be opened), 2 unexpected failure.
#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>
#include <signal.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <time.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "haptics/scene/build_scene.h"
#include "haptics/haptic_renderer.h"
#include "haptics/loop/latest_value.h"
#include "haptics/io/lcm_io.h"
#include "haptics/scene/load_scene_config.h"
#include "haptics/loop/realtime.h"
#include "haptics/loop/servo_loop.h"
#include "pd_core/mesh/collision_model.h"
#include "pd_build/build_info.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitConfig = 1;
constexpr int kExitFailure = 2;

struct Options {
  std::string config;
  std::string lcm_url;
  std::string cache_dir;  // overrides the config's cache_dir
  double duration_s = 0.0;  // 0: until a signal
  bool check = false;
  std::string log_level = "info";
  std::string geometry_thread;        // overrides contact.geometry_thread (auto|on|off)
  std::string timing_log;             // empty: no per-tick log
  int64_t timing_log_ticks = 600000;  // records preallocated (10 min at 1 kHz)
  std::string accept_session;         // overrides lcm.accept_session
  std::string accept_device;          // overrides lcm.accept_device
};

// A device name as one key=value token: quoted, anything but [A-Za-z0-9_.-] as '?'.
std::string DeviceToken(std::string_view name) {
  std::string t = "'";
  for (char c : name) t += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-') ? c : '?';
  return t + "'";
}

std::string SummaryLine(const haptics::LoopSummary& s, const haptics::ReceiverCounts& rx) {
  char line[2048];
  std::snprintf(line, sizeof(line),
                "haptic_server summary: ticks=%lld elapsed_s=%.3f rate_hz=%.1f deadline_misses=%lld "
                "jitter_p99_us=%.1f compute_p99_us=%.1f compute_max_us=%.1f poses_received=%lld "
                "poses_rejected=%lld poses_dropped=%lld messages_malformed=%lld "
                "poses_out_of_order=%lld pose_seq_skipped=%lld pose_time_backwards=%lld "
                "force_saturations=%lld rate_limited=%lld watchdog_trips=%lld pd_invalid=%lld "
                "nonfinite_outputs=%lld realtime=%d pose_wait_p50_us=%.1f pose_wait_p99_us=%.1f "
                "source_session=%s source_device=%s source_locks=%lld source_changes=%lld "
                "poses_rejected_other_sender=%lld poses_rejected_not_pinned=%lld "
                "poses_rejected_no_identity=%lld poses_rejected_version=%lld senders_seen=%lld "
                "compute_p50_us=%.1f misses_compute=%lld misses_charged=%lld misses_stalled=%lld misses_late_wakeup=%lld "
                "late_wakeups=%lld tick_cpu_p99_us=%.1f tick_cpu_max_us=%.1f "
                "wake_latency_p50_us=%.1f wake_latency_p99_us=%.1f wake_latency_max_us=%.1f "
                "geometry_thread=%d pd_update_rate_hz=%.1f model_age_p50_ticks=%.0f "
                "model_age_p99_ticks=%.0f model_age_max_ticks=%.0f pd_held_ticks=%lld "
                "model_stale_ticks=%lld model_outdated_answers=%lld geometry_async_ticks=%lld pose_triggered=%d ticks_by_pose=%lld "
                "ticks_by_deadline=%lld",
                static_cast<long long>(s.ticks), s.elapsed_s, s.achieved_rate_hz,
                static_cast<long long>(s.deadline_misses), s.jitter_p99_us, s.compute_p99_us,
                s.compute_max_us, static_cast<long long>(rx.received),
                static_cast<long long>(s.renderer.poses_rejected.total()),
                static_cast<long long>(rx.dropped), static_cast<long long>(rx.malformed),
                static_cast<long long>(rx.out_of_order), static_cast<long long>(rx.seq_skipped),
                static_cast<long long>(rx.time_backwards),
                static_cast<long long>(s.renderer.limiter.saturated),
                static_cast<long long>(s.renderer.limiter.rate_limited),
                static_cast<long long>(s.renderer.watchdog_trips),
                static_cast<long long>(s.renderer.pd_invalid),
                static_cast<long long>(s.renderer.limiter.nonfinite), s.realtime ? 1 : 0,
                s.pose_wait_p50_us, s.pose_wait_p99_us,
                haptics_msgs::FormatSession(rx.source.source.session).c_str(),
                DeviceToken(rx.source.source.device_name()).c_str(),
                static_cast<long long>(rx.source.locks),
                static_cast<long long>(s.renderer.source_changes),
                static_cast<long long>(rx.source_rejected.other_sender),
                static_cast<long long>(rx.source_rejected.not_pinned),
                static_cast<long long>(rx.source_rejected.no_identity),
                static_cast<long long>(rx.wrong_version),
                static_cast<long long>(rx.source.senders_seen), s.compute_p50_us,
                static_cast<long long>(s.misses_compute), static_cast<long long>(s.misses_charged),
                static_cast<long long>(s.misses_stalled),
                static_cast<long long>(s.misses_late_wakeup), static_cast<long long>(s.late_wakeups),
                s.tick_cpu_p99_us, s.tick_cpu_max_us, s.wake_latency_p50_us, s.wake_latency_p99_us,
                s.wake_latency_max_us, s.geometry_thread ? 1 : 0, s.pd_update_rate_hz,
                s.model_age_p50_ticks, s.model_age_p99_ticks, s.model_age_max_ticks,
                static_cast<long long>(s.renderer.pd_held_ticks),
                static_cast<long long>(s.renderer.model_stale_ticks),
                static_cast<long long>(s.renderer.model_outdated_answers),
                static_cast<long long>(s.renderer.geometry_async_ticks), s.pose_triggered ? 1 : 0,
                static_cast<long long>(s.ticks_by_pose), static_cast<long long>(s.ticks_by_deadline));
  return line;
}

int Serve(const Options& opt, sigset_t* signals) {
  // Which build is running: its CPU level sets its speed (and the CPUs it runs on).
  spdlog::info("haptic_server {}", pd_build::Summary());
  haptics::SceneConfig config = haptics::LoadSceneConfig(opt.config);
  if (!opt.lcm_url.empty()) config.lcm.url = opt.lcm_url;
  if (!opt.geometry_thread.empty())
    config.contact.geometry_thread = opt.geometry_thread == "on"    ? haptics::GeometryThreadMode::kOn
                                     : opt.geometry_thread == "off" ? haptics::GeometryThreadMode::kOff
                                                                    : haptics::GeometryThreadMode::kAuto;
  const haptics::SceneModels models = haptics::BuildSceneModels(config, opt.cache_dir);
  spdlog::info("scene '{}': tool {}, {} objects, device {} ({} N, {} N·m), {} Hz",
               config.name, models.tool->Describe(), models.objects.size(),
               config.device.name, config.device.max_force, config.device.max_torque,
               config.servo.rate_hz);
  {
    // Triangles the loop may query (meshes; primitives are exact shapes).
    auto triangles = [](const pd::Geometry& g) { return g.model() ? g.model()->mesh().num_triangles() : 0; };
    int64_t scene_triangles = 0;
    for (const haptics::SceneObject& object : models.objects) scene_triangles += triangles(*object.geometry);
    spdlog::info("triangles: tool {}, scene objects {}", triangles(*models.tool), scene_triangles);
  }
  if (opt.check) {
    std::printf("haptic_server: %s OK\n", opt.config.c_str());
    return kExitOk;
  }

  // Pose delivery must not starve behind other work either: the threads
  // created from here on (LCM's udpm read thread, the receive thread) inherit
  // SCHED_FIFO just below the servo loop, which raises itself further.
  std::string why;
  if (config.servo.realtime_priority > 0) {
    const int io_priority = std::max(1, config.servo.realtime_priority - 10);
    if (haptics::TrySetFifoScheduling(io_priority, &why)) {
      spdlog::info("LCM threads: SCHED_FIFO priority {}", io_priority);
    } else {
      spdlog::warn("LCM threads: no real-time scheduling ({}); pose delivery may lag under load", why);
    }
  }

  // The pose's path from the socket to the tick stays on the servo's CPU:
  // LCM's udpm read thread and the pose receive thread are created pinned to
  // it (below the servo loop's priority, so they never delay a tick;
  // servo.io_on_servo_cpu: false turns this off). A wake-up
  // across CPUs costs ~10 us on a VM, and the path has two before the tick;
  // the server's own wrenches, which its socket receives too, no longer wake
  // a thread on the other CPU, where the geometry thread and the device's
  // client run. Pinned until the receive thread has started.
  const int io_cpu = config.servo.io_on_servo_cpu && config.servo.cpu >= 0 &&
                             config.servo.cpu < haptics::NumCpus()
                         ? config.servo.cpu
                         : -1;
  std::optional<haptics::ScopedCpuPin> io_pin;
  if (io_cpu >= 0) {
    io_pin.emplace(io_cpu);
    if (io_pin->ok()) {
      spdlog::info("LCM threads: pinned to CPU {} (the servo loop's)", io_cpu);
    } else {
      spdlog::warn("LCM threads: not pinned ({})", io_pin->why());
    }
  }
  // Separate LCM instances: the loop's publishes never share a transmit lock
  // with the status publishes or the receive thread.
  lcm::LCM rx(config.lcm.url);
  lcm::LCM tx(config.lcm.url);
  if (!rx.good() || !tx.good()) {
    const std::string where = opt.lcm_url.empty() ? opt.config + ": lcm.url" : "--lcm-url";
    std::fprintf(stderr, "haptic_server: %s: cannot open LCM URL '%s'\n", where.c_str(),
                 config.lcm.url.c_str());
    return kExitConfig;
  }

  haptics::LatestValue<haptics::PoseSample> poses;
  haptics::PoseSourcePin pin;
  pin.session = config.lcm.accept_session;
  pin.device = config.lcm.accept_device;
  if (!opt.accept_session.empty() && !haptics_msgs::ParseSession(opt.accept_session, &pin.session)) {
    std::fprintf(stderr,
                 "haptic_server: --accept-session: '%s' is not a non-zero 64-bit session id "
                 "(0x-prefixed hex or decimal)\n",
                 opt.accept_session.c_str());
    return kExitConfig;
  }
  if (!opt.accept_device.empty()) pin.device = opt.accept_device;
  if (pin.device.size() > haptics_msgs::kMaxDeviceNameBytes) {
    std::fprintf(stderr, "haptic_server: --accept-device: '%s' is longer than %zu bytes\n",
                 pin.device.c_str(), haptics_msgs::kMaxDeviceNameBytes);
    return kExitConfig;
  }
  const haptics::PoseSourceOptions source_options = haptics::MakePoseSourceOptions(config, pin);
  spdlog::info("pose source: {}; another sender may take over after {:.0f} ms of silence",
               pin.active() ? "only session " + (pin.session != 0 ? haptics_msgs::FormatSession(pin.session) : "any") +
                                  ", device " + (pin.device.empty() ? "any" : "'" + pin.device + "'")
                            : "first valid sender",
               1e3 * source_options.release_after_s);
  haptics::PoseReceiver receiver(&rx, config.lcm.pose_channel, &poses, source_options);
  haptics::HapticRenderer renderer(config, models);
  haptics::LcmWrenchPublisher sink(&tx, config.lcm.wrench_channel);
  haptics::ServoLoopOptions loop_options;
  loop_options.rate_hz = config.servo.rate_hz;
  loop_options.cpu = config.servo.cpu;
  loop_options.realtime_priority = config.servo.realtime_priority;
  loop_options.status_rate_hz = config.servo.status_rate_hz;
  loop_options.phase_lock.enabled = config.servo.phase_lock;
  loop_options.phase_lock.target_us = config.servo.phase_lock_target_us;
  loop_options.geometry.cpu = config.contact.geometry_cpu;
  // Pose-triggered ticks: the receiver wakes the loop when a pose arrives.
  haptics::ArrivalSignal arrivals;
  loop_options.trigger =
      config.servo.pose_triggered ? haptics::TickTrigger::kPose : haptics::TickTrigger::kFixedRate;
  loop_options.arrivals = &arrivals;
  loop_options.pose_window_us = config.servo.pose_window_us;
  receiver.set_arrival_signal(&arrivals);
  std::unique_ptr<haptics::TickLog> tick_log;
  if (!opt.timing_log.empty()) {
    // Fail now, not after the run, if the file cannot be written.
    std::FILE* probe = std::fopen(opt.timing_log.c_str(), "w");
    if (probe == nullptr) {
      std::fprintf(stderr, "haptic_server: --timing-log: cannot write '%s': %s\n", opt.timing_log.c_str(),
                   std::strerror(errno));
      return kExitConfig;
    }
    std::fclose(probe);
    tick_log = std::make_unique<haptics::TickLog>(static_cast<size_t>(opt.timing_log_ticks));
    loop_options.tick_log = tick_log.get();
  }
  if (loop_options.cpu >= haptics::NumCpus()) {
    spdlog::warn("servo.cpu {} does not exist ({} CPUs online); not pinning", loop_options.cpu,
                 haptics::NumCpus());
    loop_options.cpu = -1;
  }
  haptics::ServoLoop loop(&renderer, &poses, &sink, loop_options);

  // Everything is allocated: keep it in RAM so the loop never page-faults.
  if (!haptics::TryLockMemory(&why)) spdlog::warn("memory not locked ({}); page faults possible", why);

  spdlog::info("LCM {}: poses on {}, wrenches on {}, status on {}", config.lcm.url,
               config.lcm.pose_channel, config.lcm.wrench_channel, config.lcm.status_channel);
  receiver.StartThread();
  io_pin.reset();  // the main thread (status, signals) runs anywhere again
  loop.Start();

  const int64_t start_us = haptics::MonotonicMicros();
  // Poll at twice the status rate so that no status window is missed.
  const long status_period_ns = static_cast<long>(0.5e9 / config.servo.status_rate_hz);
  int64_t last_log_us = start_us;
  for (;;) {
    timespec wait{status_period_ns / 1'000'000'000, status_period_ns % 1'000'000'000};
    const int sig = sigtimedwait(signals, nullptr, &wait);
    if (sig == SIGINT || sig == SIGTERM) {
      spdlog::info("{}: stopping", sig == SIGINT ? "SIGINT" : "SIGTERM");
      break;
    }
    if (const haptics::LoopStatus* status = loop.status().TakeNewest()) {
      const haptics_msgs::server_status_t msg = haptics::MakeStatusMessage(*status, receiver.counts());
      rx.publish(config.lcm.status_channel, &msg);
      const int64_t now_us = haptics::MonotonicMicros();
      if (now_us - last_log_us >= 5'000'000) {
        last_log_us = now_us;
        spdlog::info("ticks {} rate {:.1f} Hz jitter p99 {:.1f} us compute p99 {:.1f} us misses {} "
                     "poses {} rejected {} (other senders {}) source {} '{}'{}",
                     msg.tick_count, msg.achieved_rate_hz, msg.period_jitter_p99_us,
                     msg.compute_p99_us, msg.deadline_misses, msg.poses_received, msg.poses_rejected,
                     msg.poses_rejected_other_sender + msg.poses_rejected_not_pinned +
                         msg.poses_rejected_no_identity + msg.poses_rejected_version,
                     haptics_msgs::FormatSession(msg.source_session), msg.source_device,
                     msg.source_alive ? "" : " (silent)");
      }
    }
    if (opt.duration_s > 0.0 && haptics::MonotonicMicros() - start_us >= opt.duration_s * 1e6) break;
  }
  loop.Stop();
  receiver.StopThread();
  std::printf("%s\n", SummaryLine(loop.Summary(), receiver.counts()).c_str());
  std::fflush(stdout);
  if (tick_log) {
    std::string error;
    if (!tick_log->WriteCsv(opt.timing_log, 1e6 / config.servo.rate_hz, &error)) {
      std::fprintf(stderr, "haptic_server: --timing-log: %s\n", error.c_str());
      return kExitFailure;
    }
    spdlog::info("timing log {}: {} ticks ({} not logged: --timing-log-ticks {})", opt.timing_log,
                 tick_log->size(), tick_log->not_logged(), opt.timing_log_ticks);
  }
  // A PolyDepth query on the geometry thread can take seconds on large
  // meshes; everything is written, so do not wait for it to end.
  if (!loop.WaitGeometryFinished(2.0)) {
    spdlog::warn("geometry thread still in a query 2 s after the stop; exiting without it");
    spdlog::default_logger()->flush();
    std::fflush(nullptr);
    std::_Exit(kExitOk);
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  // Logs on stderr: stdout carries only the summary line.
  spdlog::set_default_logger(spdlog::stderr_color_mt("haptic_server"));

  Options opt;
  CLI::App app{"6-DOF haptic rendering server: probe poses in, wrenches out, over LCM."};
  app.set_version_flag("--version", "haptic_server " + pd_build::Summary());
  app.add_option("--config", opt.config, "scene YAML file (see config/)")->required();
  app.add_option("--lcm-url", opt.lcm_url, "LCM URL, overrides lcm.url of the config");
  app.add_option("--cache-dir", opt.cache_dir,
                 "directory of the mesh precomputation cache, overrides cache_dir of the config");
  app.add_option("--duration", opt.duration_s, "stop after this many seconds (default: run until SIGINT/SIGTERM)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--geometry-thread", opt.geometry_thread,
                 "where PD queries run, overrides contact.geometry_thread of the config")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  app.add_flag("--check", opt.check, "load and validate the config, build the scene, then exit");
  app.add_option("--log-level", opt.log_level, "trace, debug, info, warn, error")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}));
  app.add_option("--timing-log", opt.timing_log,
                 "write per-tick timing (period, compute, contacts, flags, miss) as CSV to FILE at exit");
  app.add_option("--timing-log-ticks", opt.timing_log_ticks,
                 "records preallocated for --timing-log; later ticks are counted, not stored")
      ->check(CLI::Range(int64_t{1}, int64_t{100'000'000}))
      ->capture_default_str();
  app.add_option("--accept-session", opt.accept_session,
                 "render only poses of this sender session (0x-prefixed hex or decimal; "
                 "overrides lcm.accept_session)");
  app.add_option("--accept-device", opt.accept_device,
                 "render only poses of this sender device name (overrides lcm.accept_device)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitConfig;
  }
  spdlog::set_level(spdlog::level::from_str(opt.log_level));

  // Block the stop signals in every thread; the main thread waits for them.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  try {
    return Serve(opt, &signals);
  } catch (const haptics::ConfigError& e) {
    std::fprintf(stderr, "haptic_server: %s\n", e.what());
    return kExitConfig;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "haptic_server: error: %s\n", e.what());
    return kExitFailure;
  }
}
