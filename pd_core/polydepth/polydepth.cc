#include "pd_core/polydepth/polydepth.h"

#include <chrono>

#include "pd_core/polydepth/contact_regions.h"
#include "pd_core/polydepth/polydepth_search.h"

namespace pd {

const char* InitializerName(Initializer init) {
  switch (init) {
    case Initializer::kNone:
      return "none";
    case Initializer::kMotionCoherence:
      return "motion_coherence";
    case Initializer::kMaximallyClear:
      return "maximally_clear";
    case Initializer::kCentroidDifference:
      return "centroid_difference";
    case Initializer::kRandom:
      return "random";
    case Initializer::kSamplingSearch:
      return "sampling_search";
  }
  return "unknown";
}

PolyDepthSolver::PolyDepthSolver(std::shared_ptr<const CollisionModel> probe,
                                 std::shared_ptr<const CollisionModel> scene,
                                 PolyDepthOptions options)
    : probe_(std::move(probe)),
      scene_(std::move(scene)),
      options_(options),
      impl_(std::make_unique<Impl>()) {
  impl_->rng.seed(options_.seed);
  impl_->constraints.reserve(1024);
  impl_->best_constraints.reserve(1024);
  impl_->previous_constraints.reserve(1024);
  impl_->unit_constraints.reserve(1024);
  impl_->pocket_constraints.reserve(1024);
  impl_->joined.reserve(1024);
  impl_->earlier.reserve(1024);
  impl_->starts.reserve(128);
  impl_->cold_probes.start_dirs.reserve(128);
  impl_->cold_probes.start_origins.reserve(128);
  impl_->cold_probes.iterated.reserve(16);
  impl_->cold_probes.landed.reserve(128);
  impl_->inner_starts.reserve(64);
  impl_->trail.reserve(512);
  impl_->qp.unique.reserve(1024);
  impl_->qp.lambda.reserve(1024);
}

PolyDepthSolver::~PolyDepthSolver() = default;

PolyDepthSolver::Preparation PolyDepthSolver::PrepareNext(const std::function<bool()>& pause) {
  Impl& s = *impl_;
  Preparation p;
  if (!s.next_candidates.building()) return p;
  const auto t0 = std::chrono::steady_clock::now();
  ProximityCounters counters;
  const std::function<bool()> never = [] { return false; };
  p.done = s.AdvanceDeferredBuild(pause ? pause : never, &counters);
  p.lists_completed = p.done ? 1 : 0;
  p.box_tests = counters.box_tests;
  p.time_us =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  return p;
}

void PolyDepthSolver::ResetWarmStart() {
  impl_->candidates.Invalidate();
  impl_->next_candidates.Invalidate();
  impl_->previous_constraints.clear();
  impl_->witness = CollisionWitness{};
  impl_->query_witness = CollisionWitness{};
  impl_->basin_witness = CollisionWitness{};
  impl_->num_basin_witnesses = 0;
  impl_->has_previous_replaced = false;
  impl_->anchor_depth = 0.0;
  impl_->check_next = -1;
  impl_->cold_probes.pending = false;
  impl_->has_previous = false;
  impl_->has_previous_free = false;
}

PenetrationResult PolyDepthSolver::Solve(const Isometry3& X_WP, const Isometry3& X_WS,
                                         bool coherent) {
  Impl& s = *impl_;
  s.t_start = std::chrono::steady_clock::now();
  PenetrationResult result;
  ModelPair pair(*probe_, *scene_, X_WP, X_WS);
  pair.candidates = &s.candidates;
  s.record.Invalidate();
  // The localisation's distance plus room for the landing's margin (OutProject).
  s.record.distance = (options_.contact_tol + 2.0 * options_.separation_margin) * pair.size();
  pair.recorded = &s.record;
  s.front.Invalidate();  // within a query only (descent_front.h)
  pair.front = &s.front;
  s.intersection_hint.Invalidate();  // within a query only, like the front
  pair.intersection_hint = &s.intersection_hint;
  s.probe_boxes.Invalidate();
  pair.probe_boxes = &s.probe_boxes;
  s.inner_spheres.Invalidate();
  pair.inner_spheres = &s.inner_spheres;
  s.counters = ProximityCounters{};
  pair.counters = &s.counters;
  s.work_limit = options_.max_work;
  s.time_limit_us = options_.max_time_us;
  s.stopped_early = false;
  s.last_check_us = -1.0;
  s.last_check_work = -1;
  s.longest_step_us = 0.0;
  s.longest_step_work = 0;
  s.landings_cut = false;
  // Bounded time: once the budget is spent and a verified answer exists, a
  // CCD under way stops too, at a point it knows free (translational_ccd.h).
  if (s.Bounded()) pair.stop_ccd = &s.stop_ccd;
  s.list_builds = 0;
  s.list_build_us = 0.0;
  const double size = pair.size();
  const double contact_distance = options_.contact_tol * size;
  s.iterations = 0;
  s.iterated_starts = 0;
  s.constraints_q_S = Vector3::Constant(1e300);
  s.best_constraints_q_S = Vector3::Constant(1e300);
  auto finish = [&] {
    result.box_tests = s.counters.box_tests;
    result.triangle_tests = s.counters.triangle_tests;
    const auto& k = s.counters.by_kind;
    result.work.collision = k[static_cast<int>(QueryKind::kCollision)];
    result.work.localisation = k[static_cast<int>(QueryKind::kLocalisation)];
    result.work.out_projection = k[static_cast<int>(QueryKind::kOutProjection)];
    result.work.list_builds = k[static_cast<int>(QueryKind::kListBuild)];
    result.work.other = s.counters.total() - result.work.collision - result.work.localisation -
                        result.work.out_projection - result.work.list_builds;
    result.list_builds = s.list_builds;
    result.list_build_us = s.list_build_us;
    result.time_us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - s.t_start)
            .count();
    return result;
  };

  const bool warm = coherent && options_.warm_start;
  s.look_ahead = warm;  // the budget's look-ahead (polydepth_search.h)
  // While what a budget cut from a cold query is pending (cold_probes.cc),
  // the answer may still move to another basin: no list of leaf pairs is
  // built around it. (Around a deep answer a build cost ~0.7 ms: it took
  // most of each 0.9 ms query's budget and left the cold search none,
  // camel_cow held still for 50 queries stayed 77% deep.)
  const bool lists_wait = warm && s.cold_probes.pending;
  s.list_follows_iterates = warm && !lists_wait;
  // How far any probe point moved since the previous frame (m).
  // (`turn`: its rotation's share, angle times the probe's radius.)
  const bool moved_from_previous = warm && (s.has_previous || s.has_previous_free);
  const double turn =
      moved_from_previous
          ? RotationAngleBetween(s.previous_X_SP.R_SP, pair.X_SP.R_SP) * probe_->radius()
          : 0.0;
  const double motion =
      moved_from_previous ? (pair.X_SP.p_SP - s.previous_X_SP.p_SP).norm() + turn : 0.0;
  bool have_prediction = false;
  Vector3 q_pred = Vector3::Zero();
  if (warm) have_prediction = s.PredictFromPrevious(pair, options_, motion, &q_pred);
  // Keep the leaf-pair list around where this query will work
  // (candidate_list_upkeep.cc): built once the query is known to collide.
  s.build_wanted = false;
  Impl::ListPlan plan;
  if (moved_from_previous && !lists_wait)
    plan = s.PlanList(pair, options_, have_prediction, q_pred, motion);

  // The collision test at the query walks the list where it still covers
  // the query pose, else descends the hierarchies (stopping at the first
  // intersecting triangle pair; the last one is tried first).
  result.in_collision = InCollision(pair, Vector3::Zero(), &s.query_witness);
  if (result.in_collision) s.BuildPlannedList(pair, options_, plan);
  if (!result.in_collision) {
    // Remember this free pose: the next contact starts from it.
    s.has_previous = false;
    s.has_previous_free = true;
    s.previous_X_SP = pair.X_SP;
    s.previous_constraints.clear();
    s.anchor_depth = 0.0;
    s.check_next = -1;
    s.cold_probes.pending = false;
    return finish();
  }
  s.best_norm = 1e300;
  s.best_origin = Initializer::kNone;
  s.verified_q_S = Vector3::Constant(1e300);
  s.surfaces_free_q_S = Vector3::Constant(1e300);

  // 0. Incremental update, step two: from the prediction (coherent_restart.cc).
  if (have_prediction) s.CoherentUpdate(pair, options_, q_pred);
  // 1. Motion coherence: step off the previous answer along its normal by
  // about the motion since then, verify freedom, and iterate from there.
  if (warm && s.has_previous && s.best_origin == Initializer::kNone)
    s.RestartNearPreviousAnswer(pair, options_, motion, turn);
  // 1b. Coming from a free frame: out-project from where the probe was then.
  if (warm && !s.has_previous && s.has_previous_free && s.best_origin == Initializer::kNone)
    s.RestartFromFreeFrame(pair, options_);

  const bool warm_found = s.best_origin != Initializer::kNone;
  result.warm_start_failed = moved_from_previous && !warm_found;
  // 2. Cold starts: the fallback when coherence found nothing (cold_query.cc).
  // 2b-2e. Otherwise cross-checks of the coherent answer for shallower
  // basins (coherence_checks.cc), and 2f. the probes of a cold query the
  // budget stopped, where it stopped (cold_probes.cc).
  if (!warm_found) {
    s.ColdQuery(pair, options_, &result);
  } else {
    s.CheckCoherentAnswer(pair, options_, &result);
    s.ResumeColdProbes(pair, options_, &result);
  }

  // 3. Verify; fall back to a dense directional search if needed (not when
  // the budget is spent: then the answer is reported invalid instead).
  bool valid = s.BestVerified(pair);
  // 3a. Out of thin free pockets (pocket_escape.cc).
  if (valid) s.EscapePocket(pair, options_, &result);
  if (!valid && options_.num_sampling_directions > 0 && !s.stopped_early) {
    s.SamplingSearch(pair, options_);
    valid = s.BestVerified(pair);
  }

  result.valid = valid;
  result.converged = !s.stopped_early && !s.landings_cut;
  result.iterations = s.iterations;
  result.iterated_starts = s.iterated_starts;
  result.initializer = s.best_origin;
  if (s.best_origin != Initializer::kNone) {
    const Matrix3 R_WS = X_WS.linear();
    result.translation_W = R_WS * s.best_q_S;
    result.depth = s.best_norm;
    result.normal_W =
        s.best_norm > 0 ? Vector3(result.translation_W / s.best_norm) : Vector3::Zero();
    s.LocaliseAtBest(pair, contact_distance);
    result.num_contacts = static_cast<int>(s.constraints.size());
    GroupContactRegions(s.constraints, s.best_q_S, X_WS, 0.1 * size, &result);
  }
  s.has_previous_free = false;
  // The anchor follows the shallowest answer since the last cross-check
  // (or the first of a contact); see step 2.
  if (!valid)
    s.anchor_depth = 0.0;
  else if (s.anchor_depth <= 0.0 || s.best_norm < s.anchor_depth)
    s.SetAnchor(s.best_q_S);
  s.has_previous_replaced = valid && result.basin_switched;
  if (valid) {
    s.has_previous = true;
    s.previous_q_S = s.best_q_S;
    s.previous_n_S = s.best_q_S / std::max(s.best_norm, 1e-300);
    s.previous_X_SP = pair.X_SP;
    s.previous_constraints = s.constraints;
    s.BeginDeferredBuildAroundAnswer(pair, options_);
  } else {
    s.has_previous = false;
    s.previous_constraints.clear();
  }
  return finish();
}

}  // namespace pd
