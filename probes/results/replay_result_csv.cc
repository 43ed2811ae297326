#include "probes/results/replay_result_csv.h"

#include <cstdio>
#include <ostream>
#include <stdexcept>

namespace probes {

void WriteResultCsv(std::ostream& out, const Trajectory& trajectory,
                    const std::vector<PoseRecord>& records) {
  if (trajectory.size() != records.size()) {
    throw std::invalid_argument("WriteResultCsv: trajectory and records differ in length");
  }
  out << kResultCsvHeader << '\n';
  char buf[512];
  for (size_t i = 0; i < records.size(); ++i) {
    const PoseSample& s = trajectory[i];
    const PoseRecord& r = records[i];
    std::snprintf(buf, sizeof(buf), "%lld,%.6f,", static_cast<long long>(r.seq), s.t);
    out << buf;
    if (r.send_us >= 0) out << r.send_us;
    std::snprintf(buf, sizeof(buf), ",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%d", s.p_WP[0],
                  s.p_WP[1], s.p_WP[2], s.q_WP[0], s.q_WP[1], s.q_WP[2], s.q_WP[3],
                  r.answered() ? 1 : 0, r.answers);
    out << buf;
    if (r.answered()) {
      const WrenchAnswer& a = r.first;
      std::snprintf(buf, sizeof(buf), ",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%.9g,%d,%lld\n",
                    a.force[0], a.force[1], a.force[2], a.torque[0], a.torque[1], a.torque[2],
                    a.flags, a.penetration_depth, a.contact_count,
                    static_cast<long long>(r.latency_us));
      out << buf;
    } else {
      out << ",,,,,,,,,,\n";
    }
  }
}

}  // namespace probes
