#include "probes/results/replay_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "msgs/sender_identity.h"

namespace probes {
namespace {

double Norm3(const double* v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// JSON has no NaN: a statistic of no samples is written as null.
nlohmann::ordered_json NumberOrNull(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

bool AnswerFinite(const WrenchAnswer& a) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(a.force[i]) || !std::isfinite(a.torque[i])) return false;
  }
  return std::isfinite(a.penetration_depth);
}

}  // namespace

ReplaySummary Summarise(const std::vector<PoseRecord>& records, int64_t planned,
                        const SummaryLimits& limits) {
  ReplaySummary s;
  s.poses_planned = planned;
  s.force_limit_N = limits.force_limit_N;
  s.max_superseded_fraction = limits.max_superseded_fraction;
  const std::optional<double>& force_limit_N = limits.force_limit_N;
  // Walking backwards tells each unanswered pose whether a later one was answered.
  bool later_answered = false;
  for (auto r = records.rbegin(); r != records.rend(); ++r) {
    if (r->send_us < 0) continue;
    if (r->answered()) {
      later_answered = true;
    } else {
      ++(later_answered ? s.superseded : s.lost);
    }
  }
  int64_t run = 0;
  std::vector<double> latencies;
  int64_t first_send = -1;
  int64_t last_send = -1;
  for (const PoseRecord& r : records) {
    if (r.send_us < 0) continue;
    ++s.poses_sent;
    if (first_send < 0) first_send = r.send_us;
    last_send = r.send_us;
    if (!r.answered()) {
      ++s.unanswered;
      s.longest_unanswered_run = std::max(s.longest_unanswered_run, ++run);
      continue;
    }
    run = 0;
    ++s.answered;
    latencies.push_back(static_cast<double>(r.latency_us));
    s.flags_seen |= r.first.flags;
    if (!AnswerFinite(r.first)) {
      ++s.non_finite_answers;
      continue;
    }
    const double f = Norm3(r.first.force);
    s.max_force_N = std::max(s.max_force_N, f);
    s.max_torque_Nm = std::max(s.max_torque_Nm, Norm3(r.first.torque));
    if (force_limit_N && f > *force_limit_N * (1.0 + 1e-9)) ++s.over_force_limit;
  }
  s.latency_us = SummariseLatencies(std::move(latencies));
  if (first_send >= 0) s.duration_s = 1e-6 * static_cast<double>(last_send - first_send);
  return s;
}

bool ReplaySummary::ok() const { return failures().empty(); }

std::vector<std::string> ReplaySummary::failures() const {
  std::vector<std::string> f;
  if (poses_sent != poses_planned) {
    f.push_back("sent " + std::to_string(poses_sent) + " of " + std::to_string(poses_planned) +
                " poses");
  }
  if (lost > 0) {
    f.push_back(std::to_string(lost) + " poses unanswered at the end (no later answer: the server "
                "stopped answering)");
  }
  const double allowed = max_superseded_fraction * static_cast<double>(poses_sent);
  if (superseded > 0 && static_cast<double>(superseded) > allowed) {
    f.push_back(std::to_string(superseded) + " poses unanswered while later ones were answered (" +
                (max_superseded_fraction > 0.0
                     ? "tolerated: " + std::to_string(static_cast<int64_t>(allowed)) + ")"
                     : "none tolerated)"));
  }
  if (other_stream_answers > 0) {
    f.push_back(std::to_string(other_stream_answers) + " wrenches rendered another sender's stream (" +
                other_stream + ") while this replay was sending");
  }
  if (statuses_rejecting_us > 0) {
    f.push_back("the server rejected this replay's poses (" + std::to_string(statuses_rejecting_us) +
                " status messages name our session as the last rejected sender)");
  }
  if (statuses_other_source > 0) {
    f.push_back("the server's pose source was " + other_source + ", not this replay, in " +
                std::to_string(statuses_other_source) + " status messages");
  }
  if (non_finite_answers > 0) {
    f.push_back(std::to_string(non_finite_answers) + " answers with non-finite values");
  }
  if (over_force_limit > 0) {
    f.push_back(std::to_string(over_force_limit) + " answers with |force| above " +
                std::to_string(*force_limit_N) + " N");
  }
  return f;
}

nlohmann::ordered_json ToJson(const haptics_msgs::server_status_t& st) {
  return {{"utime", st.utime},
          {"tick_count", st.tick_count},
          {"target_rate_hz", st.target_rate_hz},
          {"achieved_rate_hz", st.achieved_rate_hz},
          {"period_jitter_p50_us", st.period_jitter_p50_us},
          {"period_jitter_p99_us", st.period_jitter_p99_us},
          {"period_jitter_max_us", st.period_jitter_max_us},
          {"compute_p50_us", st.compute_p50_us},
          {"compute_p99_us", st.compute_p99_us},
          {"compute_max_us", st.compute_max_us},
          {"deadline_misses", st.deadline_misses},
          {"poses_received", st.poses_received},
          {"poses_rejected", st.poses_rejected},
          {"source_session", haptics_msgs::FormatSession(st.source_session)},
          {"source_device", st.source_device},
          {"source_alive", st.source_alive},
          {"source_pinned", st.source_pinned},
          {"source_locks", st.source_locks},
          {"poses_rejected_other_sender", st.poses_rejected_other_sender},
          {"poses_rejected_not_pinned", st.poses_rejected_not_pinned},
          {"poses_rejected_no_identity", st.poses_rejected_no_identity},
          {"poses_rejected_version", st.poses_rejected_version},
          {"last_rejected_session", haptics_msgs::FormatSession(st.last_rejected_session)},
          {"senders_seen", st.senders_seen},
          {"poses_dropped", st.poses_dropped},
          {"messages_malformed", st.messages_malformed},
          {"force_saturations", st.force_saturations},
          {"watchdog_trips", st.watchdog_trips},
          {"realtime", st.realtime}};
}

nlohmann::ordered_json ToJson(const ReplaySummary& s) {
  nlohmann::ordered_json j;
  j["ok"] = s.ok();
  j["failures"] = s.failures();
  j["trajectory"] = s.trajectory;
  j["sender"] = s.sender;
  j["other_stream_answers"] = s.other_stream_answers;
  j["other_stream"] = s.other_stream;
  j["statuses_rejecting_us"] = s.statuses_rejecting_us;
  j["statuses_other_source"] = s.statuses_other_source;
  j["other_source"] = s.other_source;
  j["poses_planned"] = s.poses_planned;
  j["poses_sent"] = s.poses_sent;
  j["answered"] = s.answered;
  j["unanswered"] = s.unanswered;
  j["superseded"] = s.superseded;
  j["lost"] = s.lost;
  j["longest_unanswered_run"] = s.longest_unanswered_run;
  j["wrenches_missed"] = s.wrenches_missed;
  j["max_superseded_fraction"] = s.max_superseded_fraction;
  j["repeat_answers"] = s.repeat_answers;
  j["no_pose_answers"] = s.no_pose_answers;
  j["foreign_answers"] = s.foreign_answers;
  j["latency_us"] = {{"count", s.latency_us.count},
                     {"p50", NumberOrNull(s.latency_us.p50)},
                     {"p99", NumberOrNull(s.latency_us.p99)},
                     {"max", NumberOrNull(s.latency_us.max)},
                     {"mean", NumberOrNull(s.latency_us.mean)}};
  j["max_force_N"] = s.max_force_N;
  j["max_torque_Nm"] = s.max_torque_Nm;
  j["non_finite_answers"] = s.non_finite_answers;
  j["force_limit_N"] = s.force_limit_N ? nlohmann::ordered_json(*s.force_limit_N) : nullptr;
  j["over_force_limit"] = s.over_force_limit;
  j["flags_seen"] = s.flags_seen;
  j["max_send_lateness_us"] = s.max_send_lateness_us;
  j["duration_s"] = s.duration_s;
  j["server_status"] = s.last_status ? ToJson(*s.last_status) : nlohmann::ordered_json(nullptr);
  return j;
}

std::string FormatSummary(const ReplaySummary& s) {
  char buf[1024];
  std::string out;
  std::snprintf(buf, sizeof(buf),
                "probe_replay: %s as %s: sent %lld/%lld poses in %.2f s, answered %lld, unanswered %lld"
                " (superseded %lld, lost %lld, longest run %lld); other answers: repeat %lld,"
                " before-first-pose %lld, foreign %lld, other stream %lld\n",
                s.trajectory.c_str(), s.sender.c_str(), static_cast<long long>(s.poses_sent),
                static_cast<long long>(s.poses_planned), s.duration_s,
                static_cast<long long>(s.answered), static_cast<long long>(s.unanswered),
                static_cast<long long>(s.superseded), static_cast<long long>(s.lost),
                static_cast<long long>(s.longest_unanswered_run),
                static_cast<long long>(s.repeat_answers), static_cast<long long>(s.no_pose_answers),
                static_cast<long long>(s.foreign_answers), static_cast<long long>(s.other_stream_answers));
  out += buf;
  std::snprintf(buf, sizeof(buf),
                "probe_replay: round trip us: p50 %.0f  p99 %.0f  max %.0f  mean %.1f  (n=%zu);"
                " worst send lateness %.0f us\n",
                s.latency_us.p50, s.latency_us.p99, s.latency_us.max, s.latency_us.mean,
                s.latency_us.count, s.max_send_lateness_us);
  out += buf;
  std::snprintf(buf, sizeof(buf),
                "probe_replay: max |force| %.3f N, max |torque| %.4f N.m, non-finite %lld, "
                "over limit %lld%s, flags seen 0x%x\n",
                s.max_force_N, s.max_torque_Nm, static_cast<long long>(s.non_finite_answers),
                static_cast<long long>(s.over_force_limit),
                s.force_limit_N ? (" (limit " + std::to_string(*s.force_limit_N) + " N)").c_str()
                                : "",
                static_cast<unsigned>(s.flags_seen));
  out += buf;
  if (s.last_status) {
    const auto& st = *s.last_status;
    std::snprintf(buf, sizeof(buf),
                  "probe_replay: server status: %lld ticks at %.1f Hz, deadline misses %lld, "
                  "poses received %lld rejected %lld dropped %lld, malformed %lld, "
                  "saturations %lld, watchdog %lld, realtime %d; pose source %s '%s' (%s), "
                  "rejected senders' poses %lld\n",
                  static_cast<long long>(st.tick_count), st.achieved_rate_hz,
                  static_cast<long long>(st.deadline_misses),
                  static_cast<long long>(st.poses_received),
                  static_cast<long long>(st.poses_rejected),
                  static_cast<long long>(st.poses_dropped),
                  static_cast<long long>(st.messages_malformed),
                  static_cast<long long>(st.force_saturations),
                  static_cast<long long>(st.watchdog_trips), st.realtime,
                  haptics_msgs::FormatSession(st.source_session).c_str(), st.source_device.c_str(),
                  st.source_alive ? "alive" : "silent",
                  static_cast<long long>(st.poses_rejected_other_sender + st.poses_rejected_not_pinned +
                                         st.poses_rejected_no_identity + st.poses_rejected_version));
    out += buf;
  } else {
    out += "probe_replay: no server status message received\n";
  }
  out += s.ok() ? "probe_replay: OK\n" : "probe_replay: FAILED:";
  if (!s.ok()) {
    for (const std::string& f : s.failures()) out += " " + f + ";";
    out += "\n";
  }
  return out;
}

}  // namespace probes
