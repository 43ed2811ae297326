// The leaf-pair list a coherent query walks (CandidatePairs): where it is
// planned, built, moved with the iterates, and deferred to the caller's idle
// time (PolyDepthOptions::defer_list_builds).
#include <algorithm>
#include <chrono>
#include <cmath>

#include "pd_core/polydepth/polydepth_search.h"

namespace pd {
namespace {

// A query's iterations reach this many contact distances beyond the
// configuration a list is built or checked around (its localisations and
// their out-projections): a list must cover that much more.
constexpr double kListIterationRoom = 6.0;
// A list built while sliding is centred this fraction of its radius ahead.
constexpr double kListLead = 0.6;
// A list reaches as far as this many queries of the current motion (a fast
// slide rebuilt it every other query: those rebuilds set the median), at
// least candidate_radius and at most this many times it (a rebuild's cost
// grows with the square of the reach on a flat patch).
constexpr double kListTicks = 3.0;
constexpr double kListMaxReach = 2.0;
// No list is built for a query that would need it wider than this many
// times its usual radius.
constexpr double kListMaxNeed = 2.0;
// A list is sized for about this many entries where the contact is dense
// (see PlanList): it bounds a rebuild's work and the list's
// memory (48 B per entry). Below it a rebuild's cost is set by the leaves,
// not the reach: leaf boxes are several times the radius (bull_bunny: ~7 box
// tests per entry, 89% of them on boxes of half-diagonal under 16 radii), so
// a coarse front or front tracking would save little. Measured since: a
// rebuild that updates the last build's cut of the pair hierarchy (Ehmann
// and Lin's front tracking, with merging) tests half as many pairs, but its
// time fell ~15% on average and not at all on the large lists that set p99:
// consecutive lists are ~1.6 radii apart, so most of the front near the
// contact is tested again, and every entry must be. Carrying entries to the
// next list untested (gaps moved along their axes) kept the ones a slide
// passes along, not away from: lists grew and medians doubled. Tried and dropped:
// building the next list ahead in slices over the queries the current one
// still covers (the lists built ahead sat worse, so more rebuilds, and the
// slices landed on queries with work of their own: p99 and max work up on
// knot1_camel and fandisk_elephant; measured again with a resumable descent
// and the slice spread over the queries left: fresh builds fell ~85% but
// total work rose 30-45% and every p99 and max rose). Nor does a list swept
// along the motion (a capsule of configurations instead of a ball) last
// longer for free: on a dense patch its entries grow with its length
// (fandisk_elephant at 0.36 mm: 3.3k for the ball, 9.8k with a 1.2 mm
// sweep), so the build work per millimetre slid stays the same; builds fell
// 25-45%, p99 work did not, and fandisk's max doubled.
constexpr double kListMaxEntries = 2000.0;
// A list is built of twig pairs (CandidatePairs::Grain) where the list it
// replaces held more than this many leaf pairs; the reach cap above counts a
// twig-pair entry as this many leaf pairs. An entry holds 2.28 on average
// (measured on the benchmark's haptic paths against leaf-pair lists of the
// same centre and reach; 1.61 with one-level scene twigs), but counting it
// so capped the lists that cow_armadillo's median queries walk: median work
// 461 -> 468 (1.9) and 470 (2.3), fandisk_elephant's p99 8422 -> 8188.
// With one-level twigs on both sides, on fandisk_elephant's
// dense patch (haptic_work): p99 work 12787 -> 9930 tests, max 29261 ->
// 27048, median 250 -> 263; the other pairs' answers unchanged, their work
// within 2% (knot1_bunny p99 -7%, max +4%).
// Twig pairs everywhere made every median 15-60% dearer (a walk descends
// each entry it cannot skip: a few box tests where a leaf pair costs one).
constexpr double kTwigListLeafPairs = 1000.0;
constexpr double kTwigEntryLeafPairs = 1.5;

}  // namespace

double PolyDepthSolver::Impl::ListLeafPairs() const {
  if (!candidates.valid()) return 0.0;
  return static_cast<double>(candidates.entries().size()) *
         (candidates.grain() == CandidatePairs::Grain::kTwigPairs ? kTwigEntryLeafPairs : 1.0);
}

CandidatePairs::Grain PolyDepthSolver::Impl::NextGrain() const {
  return ListLeafPairs() > kTwigListLeafPairs ? CandidatePairs::Grain::kTwigPairs
                                              : CandidatePairs::Grain::kLeafPairs;
}

// The deferred build under way, completed in this query and put in use:
// the caller's idle time did not suffice and this query needs it (going
// on without a list after a slow query made the next ones slow too: the
// idle time of each went to nothing, a cascade on cow_armadillo's path).
void PolyDepthSolver::Impl::FinishDeferredBuild(const ModelPair& pair) {
  const auto t0 = std::chrono::steady_clock::now();
  AdvanceDeferredBuild([] { return false; }, pair.counters);
  ++list_builds;
  list_build_us +=
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
}

void PolyDepthSolver::Impl::BuildList(const ModelPair& pair, const Vector3& q_center_S,
                                      double radius) {
  const auto t0 = std::chrono::steady_clock::now();
  candidates.Build(pair, q_center_S, radius, NextGrain());
  ++list_builds;
  list_build_us +=
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
}

// A coherent iterate that has left the list's reach (a basin switch
// moving the answer by millimetres) would localise and out-project by full
// descents from here on: the list moves to it, once per query (the next
// query starts near there too). cow_armadillo: p99 work -13%, same
// answers; a second move per query made knot1_bunny's deepest queries 15%
// dearer, and moving it to step 0's targets too raised every p99 and max
// (those targets go out and back in one query).
void PolyDepthSolver::Impl::FollowWithList(const ModelPair& pair, const PolyDepthOptions& opt,
                                           double size, const Vector3& q_S) {
  const double contact_distance = opt.contact_tol * size;
  if (!list_follows_iterates || !candidates.valid() ||
      candidates.Covers(pair, q_S, q_S, kListIterationRoom * contact_distance))
    return;
  const double radius = opt.candidate_radius * size + kListIterationRoom * contact_distance;
  if (opt.defer_list_builds) {  // after the answer, around it
    WantBuild(Vector3::Zero(), radius);
    list_follows_iterates = false;
    return;
  }
  BuildList(pair, q_S, radius);
  list_follows_iterates = false;
}

// Keep the leaf-pair list around where this query will work: the
// prediction, else the configuration we restart from, with room for the
// motion and the iterations' contact distance. A new list is built only
// once the query is known to collide (BuildPlannedList), and not for a contact
// regained from a free frame: a free query needs none (building one there
// cost a lift-off's free poses up to 27k tests each on fandisk_elephant,
// against ~1.5k for the collision test's own descent), and a regained
// contact's list would have to reach back over the whole motion since the
// free frame (its out-projection records the leaf pairs it needs, and an
// iterate that leaves the old list moves it there, FollowWithList).
PolyDepthSolver::Impl::ListPlan PolyDepthSolver::Impl::PlanList(const ModelPair& pair,
                                                                const PolyDepthOptions& opt,
                                                                bool have_prediction,
                                                                const Vector3& q_pred,
                                                                double motion) {
  ListPlan plan;
  const double size = pair.size();
  const double contact_distance = opt.contact_tol * size;
  const double need =
      (have_prediction ? 0.0 : 2.0 * motion) + kListIterationRoom * contact_distance;
  const Vector3 center = have_prediction ? q_pred : previous_q_S;
  plan.need_center = center;
  plan.need = need;
  if (need > kListMaxNeed * opt.candidate_radius * size) {
    // A jump: a list wide enough to cover it would hold a large part of
    // both meshes' leaf pairs (one such build took minutes on 52k x 75k
    // triangles). The queries descend the hierarchies instead.
    candidates.Invalidate();
    next_candidates.Invalidate();
  } else if (has_previous && !candidates.Covers(pair, center, center, need)) {
    // Sliding: centre the new list ahead along the motion, where the
    // coming queries will be, so it lasts longer than one centred here.
    const Vector3 v = pair.X_SP.p_SP - previous_X_SP.p_SP;
    double reach = std::clamp(kListTicks * motion, opt.candidate_radius * size,
                              kListMaxReach * opt.candidate_radius * size);
    // A dense contact (a broad flat patch) holds many leaf pairs per
    // radius squared: judged by the list it replaces, the reach shrinks to
    // about kListMaxEntries entries (not below candidate_radius). Such a
    // list costs about five box tests per entry to build, and the CCD
    // counts every entry of the prefix it walks.
    const double entries = ListLeafPairs();
    if (entries > kListMaxEntries && candidates.radius() > 0.0) {
      const double capped = candidates.radius() * std::sqrt(kListMaxEntries / entries) - need;
      reach = std::max(opt.candidate_radius * size, std::min(reach, capped));
    }
    const double lead = have_prediction && v.norm() > 0.0 ? kListLead * reach : 0.0;
    plan.build_lead = lead > 0.0 ? Vector3(lead * v.normalized()) : Vector3::Zero();
    plan.build_center = center + plan.build_lead;
    plan.build_radius = reach + need;
    plan.build_pending = true;
  }
  return plan;
}

void PolyDepthSolver::Impl::BuildPlannedList(const ModelPair& pair, const PolyDepthOptions& opt,
                                             const ListPlan& plan) {
  if (!plan.build_pending) return;
  if (opt.defer_list_builds) {
    if (next_candidates.BuildWillCover(pair, plan.need_center, plan.need)) {
      FinishDeferredBuild(pair);
    } else {
      WantBuild(plan.build_lead, plan.build_radius);
    }
  } else {
    BuildList(pair, plan.build_center, plan.build_radius);
  }
}

// Deferred (PrepareNext): around the answer, which the query did not
// know when it found its list short. A build under way that will cover
// the answer goes on.
void PolyDepthSolver::Impl::BeginDeferredBuildAroundAnswer(const ModelPair& pair,
                                                           const PolyDepthOptions& opt) {
  const double contact_distance = opt.contact_tol * pair.size();
  if (build_wanted &&
      !next_candidates.BuildWillCover(pair, best_q_S, kListIterationRoom * contact_distance))
    next_candidates.BeginBuild(pair, best_q_S + wanted_lead, wanted_radius, NextGrain());
}

}  // namespace pd
