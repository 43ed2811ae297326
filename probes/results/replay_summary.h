#pragma once
// What a replay run amounted to: counts, latency statistics and wrench
// extremes over the first answer to every pose, plus the server's last status
// message if one arrived. Written as JSON (--summary) and printed as text.
//
// Unanswered poses are split in two. "Superseded": a later pose was answered,
// so the server went on (a fixed-rate server that takes the newest pose per
// tick drops a pose when two arrive within one tick and counts it in
// server_status_t.poses_dropped; a datagram lost on the way looks the same
// from here). "Lost": no later pose was answered either, so the server
// stopped answering. Lost poses always fail the run;
// superseded ones only beyond a tolerated fraction of the poses sent
// (default none). The longest run of consecutive unanswered poses is
// reported, not judged: a sender that stalls and then catches up sends a
// burst of which a newest-pose server can only answer the last.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "haptics_msgs/server_status_t.hpp"
#include "probes/results/latency_stats.h"
#include "probes/results/seq_matcher.h"

namespace probes {

struct ReplaySummary {
  std::string trajectory;
  std::string sender;                // our session and device name
  // The server rendered someone else while we were sending (fail the run):
  int64_t other_stream_answers = 0;  // wrenches answering another sender's live stream
  std::string other_stream;          // the first such sender's session
  int64_t statuses_rejecting_us = 0; // statuses whose last_rejected_session is ours
  int64_t statuses_other_source = 0; // statuses whose pose source is another sender
  std::string other_source;          // the first such source
  int64_t poses_planned = 0;
  int64_t poses_sent = 0;
  int64_t answered = 0;
  int64_t unanswered = 0;
  int64_t superseded = 0;            // unanswered, but a later pose was answered
  int64_t lost = 0;                  // unanswered, and no later pose was answered
  int64_t longest_unanswered_run = 0;  // consecutive unanswered poses
  int64_t repeat_answers = 0;
  int64_t no_pose_answers = 0;
  int64_t foreign_answers = 0;
  int64_t wrenches_missed = 0;       // gaps in the server's wrench seq (lost in transport)
  LatencySummary latency_us;
  double max_force_N = 0.0;          // max |f| over finite answers
  double max_torque_Nm = 0.0;        // max |tau| over finite answers
  int64_t non_finite_answers = 0;    // answers with a NaN/inf force, torque or depth
  std::optional<double> force_limit_N;
  int64_t over_force_limit = 0;      // answers with |f| above the limit
  int32_t flags_seen = 0;            // OR of the flags of all first answers
  double max_send_lateness_us = 0.0; // worst publish time after its deadline
  double duration_s = 0.0;           // first send to last send
  std::optional<haptics_msgs::server_status_t> last_status;

  // Tolerance (see the file comment); the default demands every answer.
  double max_superseded_fraction = 0.0;  // of poses sent

  // Every pose sent and answered (up to the tolerances), all finite, none
  // over the force limit, and the server rendering our stream throughout.
  bool ok() const;
  // The reasons ok() is false, one per entry; empty when ok.
  std::vector<std::string> failures() const;
};

struct SummaryLimits {
  std::optional<double> force_limit_N;
  double max_superseded_fraction = 0.0;
};

ReplaySummary Summarise(const std::vector<PoseRecord>& records, int64_t planned,
                        const SummaryLimits& limits);

nlohmann::ordered_json ToJson(const ReplaySummary& s);
nlohmann::ordered_json ToJson(const haptics_msgs::server_status_t& status);

// Several human-readable lines, ending with a newline.
std::string FormatSummary(const ReplaySummary& s);

}  // namespace probes
