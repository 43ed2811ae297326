#pragma once
// In-projection of PolyDepth: the shortest translation q satisfying a set of
// half-spaces n_i·q >= c_i (a 3D quadratic program). Solved exactly by an
// active-set method (the optimum lies on at most three planes); when that
// meets an infeasible or degenerate set, by projected Gauss-Seidel on the
// dual LCP to convergence, polished on its active planes.
#include <vector>

#include "pd_core/polydepth/contact_constraints.h"

namespace pd {

struct MinNormResult {
  Vector3 q = Vector3::Zero();
  int sweeps = 0;              // Gauss-Seidel sweeps (0: the active-set solve sufficed)
  int num_unique = 0;          // constraints left after merging duplicates
  double max_violation = 0.0;  // max(c_i - n_i·q, 0) over all constraints (m)
};

// `tol` (m) is the length below which updates count as converged and
// duplicate constraints merge. `scratch` is reused to avoid allocation.
struct MinNormScratch {
  std::vector<int> unique;
  std::vector<double> lambda;
};
MinNormResult MinNormPoint(const std::vector<ContactConstraint>& constraints, double tol,
                           MinNormScratch* scratch, int max_sweeps = 500);

}  // namespace pd
