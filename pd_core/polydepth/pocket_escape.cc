// Out of thin free pockets (Solve's step 3a).
#include <algorithm>

#include "pd_core/polydepth/out_projection.h"
#include "pd_core/polydepth/polydepth_search.h"

namespace pd {
namespace {

// A pocket check moves the answer off the feature pairs within this many
// pocket thicknesses of touching: those that bound the pocket. With all the
// answer's feature pairs (up to contact_tol away) the probe was often
// wedged: no one direction clears pairs that face each other across a
// contact, though the pocket itself opens (cow_armadillo: 3 answers on 30
// paths left in pockets).
constexpr double kPocketBoundSlack = 4.0;
// Room in pocket thicknesses, in the record made for a pocket escape (step
// 3a), for the escape's move (2-8 thicknesses on haptic_work's paths).
constexpr double kEscapeRecordRoom = 16.0;

}  // namespace

// 3a. Out of thin pockets: an answer that collides again a pocket's
// thickness further along itself sits in a sliver of free space (the probe
// against a feature that leans over the answer's direction); the next
// frame's step-off along it lands in that feature and restarts cold. The
// answer's own feature pairs flag it, a collision test confirms, and the
// answer moves off all its feature pairs at once (along the direction that
// clears them all) just far enough to be free beyond: a few pocket
// thicknesses deeper, not a different answer.
void PolyDepthSolver::Impl::EscapePocket(const ModelPair& pair, const PolyDepthOptions& opt,
                                         PenetrationResult* result) {
  const double size = pair.size();
  const double margin = opt.separation_margin * size;
  const double contact_distance = opt.contact_tol * size;
  const double thickness = opt.pocket_thickness * size;
  if (!(thickness > 0.0 && best_norm > 0.0)) return;
  LocaliseAtBest(pair, contact_distance);
  const Vector3 n = best_q_S / best_norm;
  const bool suspect =
      std::any_of(constraints.begin(), constraints.end(), [&](const ContactConstraint& c) {
        const double along = c.n_S.dot(n);
        return along < 0.0 && c.n_S.dot(best_q_S) - c.c + thickness * along < 0.0;
      });
  // The pocket's collision test, the escape's and the escaped answer's
  // localisation all lie within a few thicknesses of the answer. Where
  // neither the record nor the list answers for them (a budget-stopped
  // search leaves no record at its answer), one localisation here records
  // the leaf pairs they need, with room for the move, and they walk them
  // instead of descending each (cow_armadillo under a 900 us budget: the
  // finish's collision tests 3989 -> 845). Unbounded, the same work and
  // answers on haptic_work's 30 paths (the record or list always answers).
  const double escape_reach = contact_distance + kEscapeRecordRoom * thickness;
  if (suspect && !record.Covers(best_q_S, best_q_S, kEscapeRecordRoom * thickness) &&
      !(candidates.valid() && candidates.Covers(pair, best_q_S, best_q_S, escape_reach))) {
    record.Invalidate();
    record.distance = std::max(record.distance, escape_reach + 2.0 * margin);
    CollectContactConstraints(pair, best_q_S, contact_distance, &constraints, &record);
  }
  if (suspect && InCollision(pair, best_q_S + thickness * n)) {
    ++result->pocket_escapes;
    // A free q that is free a thickness further along itself too; with
    // `move_back`, moved back in along itself to where the probe touches
    // (so the answer is again exactly where it leaves along itself).
    auto escape_to = [&](Vector3 q, bool move_back) {
      if (InCollision(pair, q) || InCollision(pair, q + thickness * q.normalized())) return false;
      bool touched = false;
      const Vector3 e = move_back ? OutProject(pair, q, Vector3::Zero(), margin, &touched) : q;
      // (A budget-stopped out-projection may not move: e == q, tested above.)
      if (touched && e != q && !InCollision(pair, e + thickness * e.normalized())) q = e;
      best_q_S = q;
      best_norm = q.norm();
      verified_q_S = q;
      constraints_q_S = Vector3::Constant(1e300);
      return true;
    };
    // Off the feature pairs that bound the pocket (those within a few
    // thicknesses of touching; the others are far at this scale) at once.
    pocket_constraints.clear();
    for (const ContactConstraint& c : constraints)
      if (c.n_S.dot(best_q_S) - c.c <= kPocketBoundSlack * thickness)
        pocket_constraints.push_back(c);
    double clearance = 0.0;
    const Vector3 d = ClearingDirection(pocket_constraints, opt.convergence_tol, &clearance);
    // The shortest move off them (the first) is not moved back: on
    // haptic_work's 30 paths all 189 escapes were, each gaining 2.0
    // thicknesses (0.02-0.06% of the depth) for an out-projection and a
    // collision test in a broad contact (1.5-2.6k tests).
    bool escaped = false;
    const double t0 = 2.0 * thickness / std::max(clearance, 1e-3);
    for (double t = t0; !escaped && clearance > 0.0 && t < 16.0 * contact_distance; t *= 4.0)
      escaped = escape_to(best_q_S + t * d, t > t0);
    // Wedged (no direction clears them all) or still inside: through the
    // pocket's far wall along the answer's own direction, and back in to
    // where the probe touches it from outside.
    for (double t = 2.0 * thickness; !escaped && t < 16.0 * contact_distance; t *= 4.0)
      escaped = escape_to(best_q_S + t * n, true);
  }
}

}  // namespace pd
