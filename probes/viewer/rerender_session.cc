#include "probes/viewer/rerender_session.h"

#include <algorithm>
#include <cmath>

#include "haptics/haptic_renderer.h"
#include "probes/results/latency_stats.h"

namespace probes {

RerenderedSession RerenderSession(const haptics::SceneConfig& config,
                                  const haptics::SceneModels& models, const Session& session) {
  // Every tick queries the geometry itself (no geometry thread): the
  // recomputation is deterministic, one answer per recorded pose.
  haptics::SceneConfig sync_config = config;
  sync_config.contact.geometry_thread = haptics::GeometryThreadMode::kOff;
  haptics::HapticRenderer renderer(sync_config, models);
  const double dt = renderer.dt();
  RerenderedSession out;
  out.frames.reserve(session.frames.size());
  std::vector<double> diffs;
  const int64_t t0_us = session.frames.front().send_us;
  int64_t tick = -1;
  for (const SessionFrame& fr : session.frames) {
    // The tick slot of this pose; the ticks in between ran with no new pose.
    const int64_t slot = std::max<int64_t>(
        tick + 1, std::llround(1e-6 * static_cast<double>(fr.send_us - t0_us) / dt));
    while (tick + 1 < slot) renderer.Tick(++tick * dt, nullptr);
    haptics::PoseSample pose;
    pose.seq = fr.seq;
    pose.utime = fr.send_us;
    pose.p_WD = fr.p_WD;
    pose.q_WD = fr.q_WD;
    pose.receive_time_ns = fr.send_us * 1000;
    const haptics::WrenchOutput& w = renderer.Tick(++tick * dt, &pose);

    RenderedFrame rf;
    rf.X_WT = renderer.tool().X_W;
    rf.f_W = w.wrench.f_W;
    const haptics::ContactGeometry& contact = renderer.geometry();
    for (int i = 0; i < contact.num_objects(); ++i) {
      const pd::PenetrationResult& r = contact.last_result(i);
      if (!r.in_collision || !r.valid) continue;
      for (int k = 0; k < r.num_regions; ++k) {
        rf.contacts.push_back({r.regions[k].p_W, r.regions[k].n_W, r.regions[k].local_depth});
      }
    }
    if (fr.answered) {
      diffs.push_back((rf.f_W - fr.f_W).norm());
      out.agreement.max_recorded_force = std::max(out.agreement.max_recorded_force, fr.f_W.norm());
    }
    out.frames.push_back(std::move(rf));
  }
  RerenderAgreement& a = out.agreement;
  a.compared = static_cast<int64_t>(diffs.size());
  if (!diffs.empty()) {  // the nearest-rank summary of the replay's latencies serves any samples
    const LatencySummary d = SummariseLatencies(diffs);
    a.median_force_diff = d.p50, a.p99_force_diff = d.p99, a.max_force_diff = d.max;
  }
  return out;
}

}  // namespace probes
