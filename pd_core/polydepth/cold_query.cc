// A cold query (Solve's step 2): the support-plane (maximally clear) and
// centroid starts landed on the contact space, the closest iterated, then
// the shell and inner probes for shallower basins (cold_probes.cc), and a
// final polish of the best answer's local model.
#include <algorithm>
#include <random>

#include "pd_core/geometry/fibonacci_sphere.h"
#include "pd_core/polydepth/out_projection.h"
#include "pd_core/polydepth/polydepth_search.h"

namespace pd {
namespace {

// A cold query ranks the best num_maximally_clear of at least this many
// support-plane directions.
constexpr int kMinSupportDirections = 48;
// Under a budget, a cold query's landings stop once this share of the
// search's part of it (kSearchShare) is spent (with one landed): the rest
// iterates the closest landing. On 24
// random cases of 13 real pairs at max_time_us 1000: mean error 19, 17
// and 16% at 0.25, 0.5 and 0.8 (at 3000: 8.1, 8.5, 8.4%).
constexpr double kColdLandingShare = 0.5;

}  // namespace

void PolyDepthSolver::Impl::ColdQuery(const ModelPair& pair, const PolyDepthOptions& opt,
                                      PenetrationResult* result) {
  const double size = pair.size();
  const double margin = opt.separation_margin * size;
  const double contact_distance = opt.contact_tol * size;
  trail.clear();
  trail_start = 0;
  join_distance = opt.cold_join * size;
  starts.clear();
  // Random directions drawn afresh from the seed (same query, same answer).
  rng.seed(opt.seed);
  const int num_clear = opt.num_maximally_clear;
  const int num_iterated = Bounded()
                               ? std::min(opt.num_iterated_starts, opt.num_iterated_starts_bounded)
                               : opt.num_iterated_starts;
  ComputeSupportPlaneStarts(pair, std::max(num_clear, kMinSupportDirections), &support_starts);
  // Maximally clear: the best support-plane separations of the two models.
  for (int i = 0; i < std::min<int>(num_clear, support_starts.size()); ++i)
    starts.push_back({support_starts[i].q_S, Initializer::kMaximallyClear});
  if (opt.use_centroid) {
    const Vector3 d = pair.X_SP * pair.P.centroid() - pair.S.centroid();
    if (d.norm() > 1e-9 * size)
      starts.push_back(
          {SupportPlaneTranslation(pair, d.normalized()), Initializer::kCentroidDifference});
  }
  std::normal_distribution<double> gauss;
  for (int i = 0; i < opt.num_random; ++i) {
    Vector3 u(gauss(rng), gauss(rng), gauss(rng));
    if (u.norm() < 1e-9) continue;
    starts.push_back({SupportPlaneTranslation(pair, u.normalized()), Initializer::kRandom});
  }
  // Their directions, for what a budget-stopped query leaves to the next
  // ones (cold_probes.cc).
  cold_probes.Reset(1);
  cold_probes.start_dirs.clear();
  cold_probes.start_origins.clear();
  cold_probes.iterated.clear();
  for (Start& st : starts) {
    st.index = static_cast<int>(cold_probes.start_dirs.size());
    cold_probes.start_dirs.push_back(st.q_S.normalized());
    cold_probes.start_origins.push_back(st.origin);
  }
  // Out-project every start once, then iterate from the closest few.
  // Once num_iterated starts have landed, a start's CCD stops as soon as
  // it has a contact before where it would land closer than the
  // num_iterated-th closest so far: that start is not iterated, so its
  // exact landing point is not needed (the iterated ones are the same).
  landed_norms.clear();
  double best_landing = 1e300;
  for (size_t k = 0; k < starts.size(); ++k) {
    Start& st = starts[k];
    // Bounded: the landings take at most kColdLandingShare of the search's
    // share of the budget once one has landed; the rest iterates the
    // closest so far.
    if (!landed_norms.empty() && BudgetSpent(kColdLandingShare * kSearchShare)) {
      landings_cut = true;
      starts.resize(k);
      break;
    }
    st.contact_norm = 1e300;
    ++result->starts;
    double threshold = 1e300;
    if (num_iterated > 0 && !landed_norms.empty()) {
      // A landing farther than the num_iterated-th closest so far, or
      // than cold_start_gate above the closest (it lands above the best
      // answer by more than the gate: not iterated), needs no exact
      // landing point.
      threshold = (1.0 + opt.cold_start_gate) * best_landing;
      if (static_cast<int>(landed_norms.size()) >= num_iterated) {
        std::nth_element(landed_norms.begin(), landed_norms.begin() + (num_iterated - 1),
                         landed_norms.end());
        threshold = std::min(threshold, landed_norms[num_iterated - 1]);
      }
    }
    bool exact = true;
    if (!LandStart(pair, margin, st.q_S, threshold, &st.contact_q_S, &exact)) continue;
    st.contact_norm = st.contact_q_S.norm();
    if (!exact) continue;
    landed_norms.push_back(st.contact_norm);
    best_landing = std::min(best_landing, st.contact_norm);
    // A landing is free (the CCD's): the answer so far, should the
    // budget end the query before any iteration.
    Offer(st.contact_q_S, st.origin);
  }
  std::sort(starts.begin(), starts.end(),
            [](const Start& a, const Start& b) { return a.contact_norm < b.contact_norm; });
  // With a screening tolerance the starts iterate only until their steps
  // gain less than it; the best of them then goes on to convergence_tol.
  const bool screen = opt.cold_screen_tol > opt.convergence_tol;
  PolyDepthOptions screen_options = opt;
  if (screen) screen_options.convergence_tol = opt.cold_screen_tol;
  for (int i = 0; i < std::min<int>(num_iterated, starts.size()); ++i) {
    if (starts[i].contact_norm >= 1e300) break;
    if (i > 0 && OutOfBudget()) break;
    // After the first, only starts landing near the best answer so far
    // (the starts are sorted by landing).
    if (i > 0 && starts[i].contact_norm > (1.0 + opt.cold_start_gate) * best_norm) break;
    // After the first, a start stops once it cannot beat the best answer.
    StartAbandon abandon(best_norm);
    cold_probes.iterated.push_back(starts[i].index);
    EndStart(Iterate(pair, screen_options, size, starts[i].contact_q_S, starts[i].origin,
                     i > 0 && opt.cold_abandon ? &abandon : nullptr));
  }
  // Bounded, the landings may have stopped early and fewer starts are
  // iterated: the following queries land and iterate them (stage 0).
  const bool starts_left =
      Bounded() && (landings_cut || stopped_early || num_iterated < opt.num_iterated_starts);
  if (screen && best_origin != Initializer::kNone && !OutOfBudget())
    EndStart(Iterate(pair, opt, size, best_q_S, best_origin));
  // Probes from the inside for shallower basins: the shell just inside the
  // answer, then pockets deeper inside it (cold_probes.cc). What the budget
  // cut, the following coherent queries go on with: the starts first if
  // any were left (and then the probes again from the beginning, at their
  // answer), else the probes where they stopped.
  inner_starts.clear();
  if (best_origin != Initializer::kNone) {
    cold_probes.pending = !RunColdProbes(pair, opt, result);
    if (starts_left) {
      inner_starts.clear();
      cold_probes.Reset(0);
      cold_probes.pending = true;
    }
  }
  // The best answer's local model may put its optimum a little shorter
  // than where its start stopped: within convergence_tol, a fraction of
  // the pair's size, coarse next to a shallow answer (a needle lying 1 mm
  // into a face ended 0.4% deep of it with one iterated start). Taken if
  // free.
  if (best_origin != Initializer::kNone && !OutOfBudget()) {
    LocaliseAtBest(pair, contact_distance);
    joined.assign(constraints.begin(), constraints.end());
    for (ContactConstraint& c : joined) c.c += margin;
    const Vector3 q_new = MinNormPoint(joined, 1e-9 * size, &qp).q;
    if (q_new.norm() < best_norm - 1e-9 * size &&
        (q_new - best_q_S).norm() < kTargetFirstSteps * contact_distance &&
        LocaliseIfFree(pair, q_new, contact_distance, nullptr))
      Offer(q_new, best_origin);
  }
  join_distance = 0.0;
}

void PolyDepthSolver::Impl::SamplingSearch(const ModelPair& pair, const PolyDepthOptions& opt) {
  const double size = pair.size();
  const double margin = opt.separation_margin * size;
  best_norm = 1e300;
  best_origin = Initializer::kNone;
  Vector3 best_contact = Vector3::Zero();
  double best_landing = 1e300;
  const int n = opt.num_sampling_directions;
  for (int i = 0; i < n; ++i) {
    const Vector3 u = FibonacciDirection(i, n);
    bool touched = false;
    const Vector3 q_c =
        OutProject(pair, SupportPlaneTranslation(pair, u), Vector3::Zero(), margin, &touched);
    if (touched && q_c.norm() < best_landing) best_landing = q_c.norm(), best_contact = q_c;
  }
  if (best_landing < 1e300) Iterate(pair, opt, size, best_contact, Initializer::kSamplingSearch);
}

bool PolyDepthSolver::Impl::LandStart(const ModelPair& pair, double margin, const Vector3& q_S,
                                      double threshold, Vector3* q_c, bool* exact) {
  // Landing at s lies (1 - s + margin / len) |q_S| from the query
  // (OutProject); contacts before s_stop land farther than the threshold
  // (by a relative 1e-9, against round-off).
  const double len = q_S.norm();
  const double s_stop =
      len > 0.0 && threshold < 1e300 ? 1.0 + margin / len - threshold / len - 1e-9 : -1.0;
  // (Never for a threshold that is a landing: landings lie at least the
  // margin from the query.)
  if (s_stop >= 1.0) return false;
  // Colliding where it would land at the threshold, it lands farther:
  // out of the running, settled by a collision test (~140 tests) instead
  // of a sweep from outside the models (~1k). Same answers; on 24 random
  // cases of 13 real pairs the cold median -40-53% (cow_cow 6.2 -> 3.7
  // ms, dragon_dragon 12.8 -> 6.0 ms). No collision witness: the last
  // direction's intersecting pair and its neighbours (16 triangle tests)
  // never intersect along the next (1.9% fewer tests without). The
  // models' inner spheres settle most of these (and the inner probes'
  // tests) before any BVH test: same answers on 24 random cases of 13
  // real pairs, collision work -33-65%, medians -5-24% (a mesh that is
  // not closed has no spheres: dragon_dragon unchanged).
  if (s_stop > 0.0 && InCollisionExpectingDepth(pair, (1.0 - s_stop) * q_S)) return false;
  bool touched = false;
  *exact = true;
  *q_c = OutProject(pair, q_S, Vector3::Zero(), margin, &touched, s_stop, exact);
  return touched;
}

}  // namespace pd
