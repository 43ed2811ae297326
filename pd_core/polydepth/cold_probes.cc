// A cold query's probes from the inside (Solve's step 2, after the iterated
// starts): free configurations shallower than the best answer, each
// out-projected toward the query and iterated like a start. Stopped by a
// time or work budget, they and the starts the budget cut go on over the
// following coherent queries (step 2f), so a budget-bounded caller (the
// haptic server's geometry thread) gets the whole cold search within a few
// queries instead of keeping a cut one's answer for as long as the contact
// lasts.
#include <algorithm>
#include <initializer_list>

#include "pd_core/polydepth/out_projection.h"
#include "pd_core/polydepth/polydepth_search.h"

namespace pd {
namespace {

// PolyDepthOptions::cold_shell_probes: probed at this fraction of the best
// answer's length (0.995 against 0.98 and 0.99, with one iterated start:
// 0.57 against 0.71 and 0.65% mean |error| on bench_pd's random scenario,
// the same time; 0.998 the same as 0.995), and the first this many free
// ones iterated (2, 4 or 8: the same answers; a free shell probe is rare,
// 0.1 per query).
constexpr double kShellRadius = 0.995;
constexpr int kShellIterated = 4;
// PolyDepthOptions::cold_inner_probes' fractions, deeper first (the first
// free ones are the most promising), and how many free ones are iterated.
constexpr double kInnerFractions[] = {0.7, 0.9};
constexpr int kInnerIterated = 2;
// Directions of PolyDepthOptions::cold_deep_probes (96 against 48 or 192:
// the same torus-knot error as 192 at three quarters of its work).
constexpr int kDeepProbeDirections = 96;
constexpr double kDeepFractions[] = {0.3, 0.5};

// The stages: the shell (the other basins just shallower than the answer),
// then pockets deeper inside the (possibly shallower) answer: the inner
// probes and, after them on a denser set of directions, the deep ones
// (which must not displace them: see cold_deep_probes). Stage 0, the
// starts, runs in the queries after a budget-stopped cold query only.
constexpr int kNumStages = 3;

}  // namespace

bool PolyDepthSolver::Impl::RunColdProbes(const ModelPair& pair, const PolyDepthOptions& opt,
                                          PenetrationResult* result) {
  const double size = pair.size();
  const double margin = opt.separation_margin * size;
  ColdProbes& p = cold_probes;
  auto stage_on = [&](int stage) {
    return stage == 1 ? opt.cold_shell_probes > 0 : opt.cold_inner_probes > 0;
  };
  auto num_sets = [&](int stage) { return stage == 1 ? 1 : opt.cold_deep_probes > 0 ? 2 : 1; };
  // Probes set `set` of the current stage on from the cursor; true once done.
  auto probe_set = [&](int set) {
    if (p.stage == 1)
      return InnerProbeStarts(pair, best_norm, opt.cold_shell_probes, {kShellRadius},
                              kShellIterated, &inner_starts, stop_ccd, &p.cursor);
    if (set == 0)
      return InnerProbeStarts(pair, best_norm, opt.cold_inner_probes,
                              {kInnerFractions[0], kInnerFractions[1]}, kInnerIterated,
                              &inner_starts, stop_ccd, &p.cursor);
    return InnerProbeStarts(pair, best_norm, kDeepProbeDirections,
                            {kDeepFractions[0], kDeepFractions[1]}, opt.cold_deep_probes,
                            &inner_starts, stop_ccd, &p.cursor);
  };
  for (; p.stage < kNumStages; ++p.stage) {
    if (p.stage == 0) {
      if (!RestOfColdStarts(pair, opt, result)) return false;
      continue;
    }
    if (!stage_on(p.stage)) continue;
    if (!p.probed) {
      // A stage begins only with budget left.
      const bool beginning = p.set == 0 && p.cursor.fraction == 0 && p.cursor.direction == 0;
      if (beginning && OutOfBudget()) return false;
      for (; p.set < num_sets(p.stage); ++p.set, p.cursor = ProbeCursor{})
        if (!probe_set(p.set)) return false;
      p.probed = true;
      p.next = 0;
    }
    for (; p.next < inner_starts.size(); ++p.next) {
      if (OutOfBudget()) return false;
      const Vector3 q0 = inner_starts[p.next];
      ++result->starts;
      // Found free at an earlier query's pose: free at this one?
      if (p.next < p.earlier && InCollision(pair, q0)) continue;
      bool touched = false;
      const Vector3 q_c = OutProject(pair, q0, Vector3::Zero(), margin, &touched);
      if (!touched) continue;
      StartAbandon abandon(best_norm);
      EndStart(Iterate(pair, opt, size, q_c, Initializer::kMaximallyClear,
                       opt.cold_abandon ? &abandon : nullptr));
    }
    inner_starts.clear();
    p.ResetProbes();
  }
  p.pending = false;
  return true;
}

bool PolyDepthSolver::Impl::RestOfColdStarts(const ModelPair& pair, const PolyDepthOptions& opt,
                                             PenetrationResult* result) {
  const double size = pair.size();
  const double margin = opt.separation_margin * size;
  const double gate = 1.0 + opt.cold_start_gate;
  ColdProbes& p = cold_probes;
  const size_t num_iterated = static_cast<size_t>(std::max(opt.num_iterated_starts, 0));
  // Each start landed at this query's pose. As in the cold query, only a
  // landing closer than the gate above the answer (and, once that many have
  // landed, than the num_iterated_starts-th closest) can be iterated and
  // needs an exact landing point; a collision test settles most others.
  for (; p.next_landing < p.start_dirs.size(); ++p.next_landing) {
    if (OutOfBudget()) return false;
    ++result->starts;
    double threshold = gate * best_norm;
    if (num_iterated > 0 && p.landed.size() >= num_iterated) {
      std::nth_element(p.landed.begin(), p.landed.begin() + (num_iterated - 1), p.landed.end());
      threshold = std::min(threshold, p.landed[num_iterated - 1].first);
    }
    Vector3 q_c;
    bool exact = true;
    if (LandStart(pair, margin, SupportPlaneTranslation(pair, p.start_dirs[p.next_landing]),
                  threshold, &q_c, &exact) &&
        exact)
      p.landed.push_back({q_c.norm(), static_cast<int>(p.next_landing)});
  }
  if (!p.landings_sorted) {
    std::sort(p.landed.begin(), p.landed.end());
    p.landings_sorted = true;
    p.next_iterated = 0;
  }
  // The closest num_iterated_starts, nearest first, while within the gate
  // above the answer; those the cold query iterated are done. Each is
  // landed again here (a landing at an earlier query's pose may collide at
  // this one).
  for (; p.next_iterated < std::min(num_iterated, p.landed.size()); ++p.next_iterated) {
    if (OutOfBudget()) return false;
    const auto [norm, k] = p.landed[p.next_iterated];
    if (norm > gate * best_norm) break;
    if (std::find(p.iterated.begin(), p.iterated.end(), k) != p.iterated.end()) continue;
    bool touched = false;
    const Vector3 q_c = OutProject(pair, SupportPlaneTranslation(pair, p.start_dirs[k]),
                                   Vector3::Zero(), margin, &touched);
    if (!touched) continue;
    p.iterated.push_back(k);
    EndStart(Iterate(pair, opt, size, q_c, p.start_origins[k]));
  }
  // The probes go on at the (possibly shorter) answer, from the beginning.
  inner_starts.clear();
  p.ResetProbes();
  return true;
}

// 2f. What a budget-stopped cold query left, at this query's pose
// and answer (the free probes it had found are tested again here first).
void PolyDepthSolver::Impl::ResumeColdProbes(const ModelPair& pair, const PolyDepthOptions& opt,
                                             PenetrationResult* result) {
  if (!cold_probes.pending || best_origin == Initializer::kNone) return;
  cold_probes.earlier = inner_starts.size();
  result->cold_probes_resumed = true;
  RunColdProbes(pair, opt, result);
}

}  // namespace pd
