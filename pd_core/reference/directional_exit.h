#pragma once
// The reference's directional exit: the first free translation of the probe
// along a direction u, exact from the triangle pairs' touching intervals
// (pair_interval.h), with containment between them by ray parity. Part of
// the slow independent reference (reference_pd.h).
#include <vector>

#include "pd_core/reference/pair_interval.h"
#include "pd_core/reference/placed_pair.h"

namespace pd {
namespace reference {

struct Box2 {
  double x0, x1, y0, y1;  // projected bounds, inflated by eps_len
  double h0, h1;          // range along u
  int tri;
};

// Per-direction buffers, reused across directions of one query.
struct DirectionalScratch {
  std::vector<Proj> proj_P, proj_S;
  std::vector<TriProj> tris_P, tris_S;
  std::vector<Box2> boxes_P, boxes_S;
  std::vector<std::vector<Box2>> bands_P, bands_S;
  std::vector<int> active_P, active_S;
  std::vector<Interval> intervals;
};

// Unit vectors e1, e2 completing u to a right-handed frame; exact for axes.
void Complete(const Vector3& u, Vector3* e1, Vector3* e2);

struct Exit {
  bool colliding = false;  // at s = 0
  double distance = 0.0;   // first free s >= 0 (m), 0 if not colliding
  // Unit contact normal where P leaves S, in world, oriented along u; zero if
  // undefined. Moving along it is locally the shortest way off that contact.
  Vector3 normal_W = Vector3::Zero();
};

// known_colliding skips the containment test at s = 0 when the caller already
// knows P collides there. With a finite cutoff (m) the caller only needs exits
// below it: pairs that touch only beyond it are skipped, and an exit at or
// beyond it is reported as infinity.
Exit DirectionalExit(const PairGeometry& g, const Vector3& u, double slit_tol_abs,
                     bool known_colliding, double cutoff, DirectionalScratch* sc);

}  // namespace reference
}  // namespace pd
