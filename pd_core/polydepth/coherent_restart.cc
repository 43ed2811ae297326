// A coherent query's restarts from the previous frame (Solve's steps 0, 1
// and 1b): the incremental update of the previous answer, step-offs near
// it, and a contact regained from a free frame.
#include <algorithm>
#include <array>

#include "pd_core/polydepth/out_projection.h"
#include "pd_core/polydepth/polydepth_search.h"

namespace pd {
namespace {

// The prediction is a first-order model of a small motion: after a jump
// (more than kPredictionMotion of the pair's size since the last answer)
// the contact may have changed shape and the restarts decide.
constexpr double kPredictionMotion = 5e-3;
// A coherent restart's step-offs of 1 and 4 motions (along the previous
// answer and with the motion undone) come first in its list of candidates;
// the clearing direction is tried before the rest (step 1).
constexpr int kNearStepOffs = 4;

}  // namespace

// Incremental update, step one: the previous answer's feature pairs,
// re-evaluated at the new pose, predict the new local contact model; its
// in-projection q_pred predicts the answer (no geometry query needed).
bool PolyDepthSolver::Impl::PredictFromPrevious(const ModelPair& pair, const PolyDepthOptions& opt,
                                                double motion, Vector3* q_pred) {
  const double size = pair.size();
  const double margin = opt.separation_margin * size;
  if (!has_previous || previous_constraints.empty() || !(motion <= kPredictionMotion * size))
    return false;
  RefreshContactConstraints(pair, previous_q_S, previous_constraints, &constraints);
  for (ContactConstraint& c : constraints) c.c += margin;
  *q_pred = MinNormPoint(constraints, opt.convergence_tol * size, &qp).q;
  return q_pred->allFinite();
}

// 0. Incremental update, step two: from the prediction, localise and test
// the surfaces in one pass; while the configuration is free, in-project on
// what was found there and try the result the same way (a free target
// needs no out-projection). Stops at a local optimum, or hands a colliding
// target to the out-projecting iteration from the last free point.
void PolyDepthSolver::Impl::CoherentUpdate(const ModelPair& pair, const PolyDepthOptions& opt,
                                           const Vector3& q_pred) {
  const double size = pair.size();
  const double margin = opt.separation_margin * size;
  const double contact_distance = opt.contact_tol * size;
  const double tol = opt.convergence_tol * size;
  Vector3 q = q_pred;
  for (int k = 0; k < opt.max_iterations; ++k) {
    if (OutOfBudget()) break;
    if (!LocaliseIfFree(pair, q, contact_distance, &witness)) break;
    if (constraints.empty()) {
      // Free but off the contact space (the probe moved away from the
      // contact): land on it toward the query, then go on from there
      // (recording: the localisation there walks the sweep's pairs; it
      // descended both hierarchies again, 2.5k tests on knot1_bunny's
      // deepest queries).
      bool touched = false;
      const Vector3 q_c = OutProjectRecording(pair, q, Vector3::Zero(), margin, &touched, &record);
      if (!touched) break;
      if (!(q_c.norm() < q.norm() - tol)) {
        // It touches where it stands, yet no feature pair there gives a
        // half-space (a degenerate contact: parallel edges, a pair on no
        // face of the Minkowski difference): q is this step's answer.
        // Landing again would land on itself: one query did so 40 times,
        // 36k tests (cow_armadillo on a seeded path).
        Offer(q, Initializer::kMotionCoherence);
        break;
      }
      q = q_c;
      continue;
    }
    ++iterations;
    Offer(q, Initializer::kMotionCoherence);
    // Each point offered here is the best answer so far (the first, then
    // strictly shorter): keep its localisation for Iterate (which goes on
    // from the last one when the next target collides) and the end.
    best_constraints = constraints;
    best_constraints_q_S = q;
    for (ContactConstraint& c : constraints) c.c += margin;
    const Vector3 q_new = MinNormPoint(constraints, tol, &qp).q;
    if (!(q_new.norm() < q.norm() - tol)) break;  // q is locally optimal
    q = q_new;
  }
  // The last target collided: continue from the last free point the usual
  // way (its out-projection lands on the contact space before the target).
  if (best_origin != Initializer::kNone && q != verified_q_S)
    Iterate(pair, opt, size, verified_q_S, Initializer::kMotionCoherence);
}

// 1. Motion coherence: step off the previous answer along its normal by
// about the motion since then, verify freedom, and iterate from there.
void PolyDepthSolver::Impl::RestartNearPreviousAnswer(const ModelPair& pair,
                                                      const PolyDepthOptions& opt, double motion,
                                                      double turn) {
  const double size = pair.size();
  const double margin = opt.separation_margin * size;
  const double contact_distance = opt.contact_tol * size;
  // Free candidates, nearest first: the previous answer stepped off along
  // its normal by about the motion; the previous answer with the motion's
  // translation undone (the probe back where it was free, off by the
  // rotation only), stepped off a little.
  const Vector3 back = previous_X_SP.p_SP - pair.X_SP.p_SP;
  const double step = motion + contact_distance, back_step = turn + contact_distance;
  const std::array<Vector3, 7> candidates = {previous_q_S + step * previous_n_S,
                                             previous_q_S + back + back_step * previous_n_S,
                                             previous_q_S + 4.0 * step * previous_n_S,
                                             previous_q_S + back + 4.0 * back_step * previous_n_S,
                                             previous_q_S + back + 16.0 * back_step * previous_n_S,
                                             previous_q_S + 16.0 * step * previous_n_S,
                                             previous_q_S + 64.0 * step * previous_n_S};
  auto try_from = [&](const Vector3& q0) {
    if (InCollision(pair, q0)) return false;
    // Verified free: an answer already (an upper bound), so a bounded
    // query may stop the out-projection from it (pair.stop_ccd).
    verified_q_S = q0;
    Offer(q0, Initializer::kMotionCoherence);
    bool touched = false;
    const Vector3 q_c = OutProjectRecording(pair, q0, Vector3::Zero(), margin, &touched, &record);
    // Stopped by the budget, its free point is not taken (as in Iterate):
    // q0 is tested in full, the point short of the contact is not.
    if (touched && !stopped_early) Iterate(pair, opt, size, q_c, Initializer::kMotionCoherence);
    return true;
  };
  const auto far = candidates.begin() + kNearStepOffs;
  bool started = std::any_of(candidates.begin(), far, try_from);
  // A feature leaning over the previous answer's direction blocks those
  // steps: step off along the direction that clears all its feature pairs,
  // 1 and 4 steps before the far step-offs above (16 and 64 steps), which
  // land far out and iterate back down (cow_armadillo on haptic_work's
  // first path: 64 steps out, landing at 7x the answer's length and 8
  // iterations back, 19.0k tests; from the clearing direction 3.9k, and
  // an answer 9% shorter).
  double clearance = 0.0;
  const Vector3 d = started
                        ? Vector3::Zero()
                        : ClearingDirection(previous_constraints, opt.convergence_tol, &clearance);
  // From q along u by k steps of 1/per along u, then with the motion
  // undone by k back steps.
  auto step_off = [&](const Vector3& q, const Vector3& u, double k, double per) {
    return try_from(q + (k * step / per) * u) || try_from(q + back + (k * back_step / per) * u);
  };
  auto try_clearing = [&](double k) {
    return clearance > 0.0 && step_off(previous_q_S, d, k, clearance);
  };
  started = started || try_clearing(1.0) || try_clearing(4.0) ||
            std::any_of(far, candidates.end(), try_from) || try_clearing(16.0);
  started = started || try_clearing(64.0);
  // The previous answer came from a neighbour-basin probe (step 2e) and
  // that basin closed over it: go on from the answer it replaced
  // (fandisk_elephant on haptic_work's seed 20240618, pose 2438: every
  // step-off of the probe's answer collided and the query restarted cold,
  // 80.6k tests, 4.1 ms).
  for (double k : {1.0, 4.0, 16.0}) {
    if (started || !has_previous_replaced) break;
    started = step_off(previous_replaced_q_S, previous_replaced_q_S.normalized(), k, 1.0);
  }
}

// 1b. Coming from a free frame: put the probe back where it was then (a
// free place a short way back along the motion) and out-project from there.
void PolyDepthSolver::Impl::RestartFromFreeFrame(const ModelPair& pair,
                                                 const PolyDepthOptions& opt) {
  const double size = pair.size();
  const double margin = opt.separation_margin * size;
  const double contact_distance = opt.contact_tol * size;
  const Vector3 back = previous_X_SP.p_SP - pair.X_SP.p_SP;
  const double len = back.norm();
  if (len > 0.0) {
    double offset = contact_distance;
    for (int attempt = 0; attempt < 3; ++attempt, offset *= 4.0) {
      const Vector3 q0 = back + offset * (back / len);
      if (InCollision(pair, q0)) continue;
      verified_q_S = q0;
      Offer(q0, Initializer::kMotionCoherence);  // verified free (see try_from above)
      bool touched = false;
      const Vector3 q_c = OutProjectRecording(pair, q0, Vector3::Zero(), margin, &touched, &record);
      if (touched) {
        Iterate(pair, opt, size, q_c, Initializer::kMotionCoherence);
      } else {
        // Free all the way: the query only touches (the CCD counts no
        // contact at the very end). Back off along the motion by the
        // margin; without this the cold starts answered from outside the
        // scene's hull, through the wall (tests/pd_core/test_hard_cases.cc).
        const Vector3 q_b = margin * (back / len);
        if (!InCollision(pair, q_b)) Iterate(pair, opt, size, q_b, Initializer::kMotionCoherence);
      }
      break;
    }
  }
}

}  // namespace pd
