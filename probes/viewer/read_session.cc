#include "probes/viewer/read_session.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <sstream>
#include <vector>

#include "haptics_msgs/probe_pose_t.hpp"
#include "haptics_msgs/wrench_t.hpp"
#include "probes/trajectory/input_error.h"
#include "probes/results/replay_result_csv.h"
#include "probes/trajectory/trajectory_lcm_log.h"

namespace probes {
namespace {

std::vector<std::string> SplitCommas(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream ss(line);
  std::string f;
  while (std::getline(ss, f, ',')) fields.push_back(f);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

// Column names of the result CSV, in order (the header is checked against them).
std::vector<std::string> Columns() { return SplitCommas(kResultCsvHeader); }

double Number(const std::vector<std::string>& fields, int column, const std::string& where) {
  const std::string& text = fields[column];
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v)) {
    throw InputError(where + ": field '" + Columns()[column] + "': '" + text +
                     "' is not a finite number");
  }
  return v;
}

Session ReadResultCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open session file");
  Session session{path, "result-csv", {}};
  std::string line;
  if (!std::getline(in, line) || line != kResultCsvHeader) {
    throw InputError(path + ":1: not an LCM log and not probe_replay's result CSV (header must be '" +
                     std::string(kResultCsvHeader) + "')");
  }
  const size_t n = Columns().size();
  enum { kSeq, kT, kSend, kX, kY, kZ, kQw, kQx, kQy, kQz, kAnswered, kAnswers, kFx, kFy, kFz,
         kTx, kTy, kTz, kFlags, kDepth, kContacts, kLatency };
  int line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    const std::string where = path + ":" + std::to_string(line_number);
    const std::vector<std::string> f = SplitCommas(line);
    if (f.size() != n) {
      throw InputError(where + ": expected " + std::to_string(n) + " fields, got " +
                       std::to_string(f.size()));
    }
    if (f[kSend].empty()) continue;  // never sent
    SessionFrame fr;
    fr.seq = static_cast<int64_t>(Number(f, kSeq, where));
    fr.t = Number(f, kT, where);
    fr.send_us = static_cast<int64_t>(Number(f, kSend, where));
    fr.p_WD = {Number(f, kX, where), Number(f, kY, where), Number(f, kZ, where)};
    fr.q_WD = pd::Quaternion(Number(f, kQw, where), Number(f, kQx, where), Number(f, kQy, where),
                             Number(f, kQz, where));
    if (std::abs(fr.q_WD.norm() - 1.0) > 1e-3) {
      throw InputError(where + ": quaternion (qw,qx,qy,qz) is not unit (norm " +
                       std::to_string(fr.q_WD.norm()) + ")");
    }
    fr.q_WD.normalize();
    fr.answered = Number(f, kAnswered, where) != 0.0;
    if (fr.answered) {
      fr.f_W = {Number(f, kFx, where), Number(f, kFy, where), Number(f, kFz, where)};
      fr.tau_W = {Number(f, kTx, where), Number(f, kTy, where), Number(f, kTz, where)};
      fr.flags = static_cast<int>(Number(f, kFlags, where));
      fr.depth = Number(f, kDepth, where);
      fr.contact_count = static_cast<int>(Number(f, kContacts, where));
      fr.round_trip_us = Number(f, kLatency, where);
    }
    session.frames.push_back(fr);
  }
  if (session.frames.empty()) throw InputError(path + ": no pose was sent in this session");
  const double t0 = session.frames.front().t;
  for (SessionFrame& fr : session.frames) fr.t -= t0;
  return session;
}

bool AllFinite(const double* v, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

Session ReadLcmLog(const std::string& path, const std::string& pose_channel,
                   const std::string& wrench_channel) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw InputError(path + ": cannot open LCM log");
  Session session{path, "lcm-log", {}};
  std::map<int64_t, size_t> frame_of_seq;  // pose seq -> index in frames
  std::map<int64_t, int64_t> log_time_of_seq;  // pose seq -> logger receive time (us)
  int event = 0;
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
    ++event;
    const std::string where = path + ": event " + std::to_string(event) + " on '" + e->channel + "'";
    if (e->channel == pose_channel) {
      haptics_msgs::probe_pose_t m{};
      if (m.decode(e->data, 0, e->datalen) != e->datalen) {
        throw InputError(where + ": cannot decode as haptics_msgs.probe_pose_t");
      }
      if (!AllFinite(m.position, 3) || !AllFinite(m.orientation, 4)) {
        throw InputError(where + ": pose seq " + std::to_string(m.seq) + " has a non-finite value");
      }
      SessionFrame fr;
      fr.seq = m.seq;
      fr.send_us = m.utime;
      fr.p_WD = {m.position[0], m.position[1], m.position[2]};
      fr.q_WD = pd::Quaternion(m.orientation[0], m.orientation[1], m.orientation[2], m.orientation[3]);
      if (std::abs(fr.q_WD.norm() - 1.0) > 1e-3) {
        throw InputError(where + ": pose seq " + std::to_string(m.seq) + " orientation is not unit");
      }
      fr.q_WD.normalize();
      if (frame_of_seq.count(m.seq) != 0) continue;  // a duplicate: the first one counts
      frame_of_seq[m.seq] = session.frames.size();
      log_time_of_seq[m.seq] = e->timestamp;
      session.frames.push_back(fr);
    } else if (e->channel == wrench_channel) {
      haptics_msgs::wrench_t w{};
      if (w.decode(e->data, 0, e->datalen) != e->datalen) {
        throw InputError(where + ": cannot decode as haptics_msgs.wrench_t");
      }
      auto it = frame_of_seq.find(w.pose_seq);
      if (it == frame_of_seq.end()) continue;  // no pose yet, or one not in the log
      SessionFrame& fr = session.frames[it->second];
      if (fr.answered) continue;  // repeats of the answer while no new pose came
      if (!AllFinite(w.force, 3) || !AllFinite(w.torque, 3)) {
        throw InputError(where + ": wrench for pose seq " + std::to_string(w.pose_seq) +
                         " is not finite");
      }
      fr.answered = true;
      fr.f_W = {w.force[0], w.force[1], w.force[2]};
      fr.tau_W = {w.torque[0], w.torque[1], w.torque[2]};
      fr.depth = w.penetration_depth;
      fr.contact_count = w.contact_count;
      fr.flags = w.flags;
      fr.round_trip_us = static_cast<double>(e->timestamp - log_time_of_seq[w.pose_seq]);
    }
  }
  if (session.frames.empty()) {
    throw InputError(path + ": no probe_pose_t events on channel '" + pose_channel + "'");
  }
  const int64_t t0 = session.frames.front().send_us;
  for (SessionFrame& fr : session.frames) fr.t = 1e-6 * static_cast<double>(fr.send_us - t0);
  return session;
}

}  // namespace

Session ReadSession(const std::string& path, const std::string& pose_channel,
                    const std::string& wrench_channel) {
  if (IsLcmLogFile(path)) return ReadLcmLog(path, pose_channel, wrench_channel);
  return ReadResultCsv(path);
}

}  // namespace probes
