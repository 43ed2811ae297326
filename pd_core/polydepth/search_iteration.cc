// A start's search (PolyDepth's iteration) and the steps it shares with the
// other phases: localisation at a configuration, the local model's
// in-projection, the free tests that go with them.
#include <algorithm>

#include "pd_core/polydepth/out_projection.h"
#include "pd_core/polydepth/polydepth_search.h"
#include "pd_core/proximity/solid_containment.h"

namespace pd {

void PolyDepthSolver::Impl::JoinEarlierConstraints(const Vector3& q_c, double distance,
                                                   bool creeping) {
  joined.assign(constraints.begin(), constraints.end());
  if (creeping) {
    for (const ContactConstraint& e : earlier) {
      if (e.n_S.dot(q_c) - e.c > distance) continue;
      const bool found =
          std::any_of(constraints.begin(), constraints.end(), [&](const ContactConstraint& c) {
            return c.kind == e.kind && c.feature_P == e.feature_P && c.feature_S == e.feature_S;
          });
      if (!found) joined.push_back(e);
    }
  }
  earlier.assign(joined.begin(), joined.end());
}
Vector3 PolyDepthSolver::Impl::Iterate(const ModelPair& pair, const PolyDepthOptions& opt,
                                       double size, Vector3 q_c, Initializer origin,
                                       StartAbandon* abandon) {
  const double tol = opt.convergence_tol * size;
  const double margin = opt.separation_margin * size;
  const double contact_distance = opt.contact_tol * size;
  Offer(q_c, origin);
  double norm_c = q_c.norm();
  bool off_contact = false;     // q_c is a reached in-projection target, not a landing
  bool localised_here = false;  // `constraints` hold q_c's localisation already
  if (abandon) abandon->Update(norm_c);
  ++iterated_starts;
  for (int it = 0; it < opt.max_iterations; ++it) {
    if (OutOfBudget()) break;
    if (JoinsAnEarlierStart(q_c, norm_c)) break;
    if (join_distance > 0.0) trail.push_back({q_c, 1e300});
    ++iterations;
    if (origin == Initializer::kMotionCoherence) FollowWithList(pair, opt, size, q_c);
    // Localise the contact space at q_c and in-project toward the query
    // (the localisation kept at the best answer is q_c's when a search
    // goes on from there: the incremental update's last free point, whose
    // localisation was repeated, up to 2.6k tests where no list covered it;
    // haptic_work total work -1.3%, cow_armadillo p99 -5%).
    if (localised_here) {
      localised_here = false;  // a reached target's test localised it (below)
    } else if (q_c == best_constraints_q_S) {
      constraints = best_constraints;
    } else if (CollectContactConstraintsIfSurfacesFree(pair, q_c, contact_distance, &constraints,
                                                       nullptr, &record)) {
      // The same pass tests the surfaces: when q_c ends the search, the
      // answer's verification needs only the containment test.
      surfaces_free_q_S = q_c;
    } else {
      // A landing whose surfaces cross (round-off): localise it in full,
      // and let the verification judge it.
      CollectContactConstraints(pair, q_c, contact_distance, &constraints, &record);
    }
    constraints_q_S = q_c;
    if (q_c == best_q_S) {
      best_constraints = constraints;
      best_constraints_q_S = q_c;
    }
    if (constraints.empty()) {
      if (!off_contact) break;
      // Reached free and nothing within reach there: land on the contact
      // space toward the query.
      off_contact = false;
      bool touched = false;
      const Vector3 q_next =
          OutProjectRecording(pair, q_c, Vector3::Zero(), margin, &touched, &record);
      if (!touched) break;
      q_c = q_next;
      norm_c = q_c.norm();
      Offer(q_c, origin);
      continue;
    }
    off_contact = false;
    // The local model: the localisation's constraints, and in a long
    // coherent search also the earlier iterates' that are still about as
    // near (by plane distance; JoinEarlierConstraints).
    JoinEarlierConstraints(q_c, contact_distance,
                           origin == Initializer::kMotionCoherence &&
                               opt.creep_join_iterations > 0 && it >= opt.creep_join_iterations);
    // Aim strictly inside free space: an exactly touching target is
    // ambiguous under round-off, a target `margin` clear is not. (The local
    // model only: `constraints` stay as localised, so a later model built
    // from them, e.g. the cold polish's, adds the margin once.)
    for (ContactConstraint& c : joined) c.c += margin;
    const Vector3 q_new = MinNormPoint(joined, tol, &qp).q;
    if (q_new.norm() >= norm_c - tol) break;  // q_c is locally optimal
    // A short step's target is usually free (the local model held the
    // contact it reaches): tested and localised there in one pass, it needs
    // no out-projection (see kTargetFirstSteps).
    if ((q_new - q_c).norm() < kTargetFirstSteps * contact_distance &&
        LocaliseIfFree(pair, q_new, contact_distance, nullptr)) {
      localised_here = true;
      off_contact = true;
      q_c = q_new;
      norm_c = q_c.norm();
      Offer(q_c, origin);
      if (abandon && abandon->Update(norm_c)) break;
      continue;
    }
    // Move toward q_new, landing on the first contact on the way.
    bool touched = false;
    Vector3 q_next = OutProjectRecording(pair, q_c, q_new, margin, &touched, &record);
    // Stopped by the budget, the sweep's free point is not taken: the
    // answer stays at q_c, whose localisation the result needs and has (at
    // the sweep's point it would cost a descent of both hierarchies, the
    // stopped sweep leaving no record: 2k tests past a 7k budget on
    // cow_armadillo, for a gain of micrometres).
    if (stopped_early && q_c == best_constraints_q_S) break;
    if (!touched) {
      // The target is free (the sweep to it from a free start met nothing)
      // and lies on the local model's boundary, usually on the contact space
      // itself: the next step localises there (a walk of the pairs the sweep
      // recorded) instead of sweeping it back toward the query first (a CCD
      // the whole depth long that lands a margin away: 2-6k tests on the
      // haptic paths' deep queries). Only where nothing is within reach
      // there does it out-project (above). Same errors on 72 reference
      // cases of 6 real pairs (bench_pd random); work on 96 cold
      // random cases of 4 real pairs -3 to -7%, haptic_work's p99 and max
      // work down up to 13% (cow_armadillo max 21126 -> 18459).
      off_contact = true;
    }
    const double norm_next = q_next.norm();
    const bool improved = norm_next < norm_c - tol;
    q_c = q_next;
    norm_c = norm_next;
    Offer(q_c, origin);
    if (!improved) break;
    if (abandon && abandon->Update(norm_c)) break;
  }
  return q_c;
}

Vector3 PolyDepthSolver::Impl::ClearingDirection(const std::vector<ContactConstraint>& cs,
                                                 double tol, double* clearance) {
  unit_constraints.assign(cs.begin(), cs.end());
  for (ContactConstraint& c : unit_constraints) c.c = 1.0;
  const Vector3 x = MinNormPoint(unit_constraints, tol, &qp).q;
  *clearance = 0.0;
  if (!(x.norm() > 0.0) || !x.allFinite()) return Vector3::Zero();
  const Vector3 d = x.normalized();
  double least = 1e300;
  for (const ContactConstraint& c : cs) least = std::min(least, c.n_S.dot(d));
  *clearance = least;
  return least > 0.0 ? d : Vector3::Zero();
}

bool PolyDepthSolver::Impl::LocaliseIfFree(const ModelPair& pair, const Vector3& q_S,
                                           double distance, CollisionWitness* witness) {
  constraints_q_S = Vector3::Constant(1e300);
  if (!CollectContactConstraintsIfSurfacesFree(pair, q_S, distance, &constraints, witness,
                                               &record) ||
      AnyComponentInside(pair, q_S))
    return false;
  constraints_q_S = q_S;
  verified_q_S = q_S;
  return true;
}

void PolyDepthSolver::Impl::LocaliseAtBest(const ModelPair& pair, double contact_distance) {
  if (constraints_q_S == best_q_S) return;
  if (best_constraints_q_S == best_q_S)
    constraints = best_constraints;
  else
    CollectContactConstraints(pair, best_q_S, contact_distance, &constraints, &record);
  constraints_q_S = best_q_S;
}

bool PolyDepthSolver::Impl::BestVerified(const ModelPair& pair) {
  return best_origin != Initializer::kNone &&
         (best_q_S == verified_q_S ||
          (best_q_S == surfaces_free_q_S ? !AnyComponentInside(pair, best_q_S)
                                         : !InCollision(pair, best_q_S)));
}

}  // namespace pd
