#pragma once
// GJK (Gilbert-Johnson-Keerthi) distance from the origin to a convex set
// given by its support function, in double precision: the closest point v of
// the set to the origin, or "contains the origin" with the final simplex
// (which seeds EPA, pd_core/convex/epa.h).
#include <array>

#include "pd_core/convex/minkowski_difference.h"

namespace pd {

struct GjkSimplex {
  std::array<Vector3, 4> points;
  int size = 0;
};

struct GjkResult {
  bool intersecting = false;  // origin within tol_abs of the set
  Vector3 v = Vector3::Zero();  // closest point of the set to the origin
  // Support point along -v at the end: -v̂·w is a lower bound on the
  // distance and h(-v̂) = -v̂·w the set's support value along -v̂.
  Vector3 w = Vector3::Zero();
  GjkSimplex simplex;
  int iterations = 0;
};

// tol_abs (m): distances below it count as intersecting; rel_tol: stop when
// the gap |v| - v̂·w between upper and lower bound is below rel_tol |v|.
// guess_W: initial search direction (any non-zero vector; zero -> +x).
GjkResult Gjk(const MinkowskiDifference& D, const Vector3& guess_W, double tol_abs,
              double rel_tol = 1e-12, int max_iterations = 64);

// Closest point to the origin of the simplex, reducing the simplex to the
// smallest sub-simplex whose hull contains that point. Returns false when the
// origin is inside a full tetrahedron (then v = 0 and the simplex is kept).
bool ClosestPointOnSimplex(GjkSimplex* simplex, Vector3* v);

}  // namespace pd
