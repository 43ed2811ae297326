#pragma once
// Reads a recorded session for the viewer, by content: an LCM log (poses on
// pose_channel, answers on wrench_channel, matched by pose_seq; the first
// answer of each pose counts, round trip from the log's receive times) or
// probe_replay's result CSV (probes/results/replay_result_csv.h; poses never sent are
// dropped). Throws InputError naming the file, line or event, and field.
#include <string>

#include "probes/viewer/session_data.h"

namespace probes {

Session ReadSession(const std::string& path, const std::string& pose_channel,
                    const std::string& wrench_channel);

}  // namespace probes
