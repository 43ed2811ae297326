#pragma once
// In-projection of PolyDepth: the shortest translation q satisfying a set of
// half-spaces n_i·q >= c_i (a 3D quadratic program). Solved through its dual
// LCP by projected Gauss-Seidel to convergence in double precision, then
// polished by an exact solve on the active set when it has at most 3 rows.
#include <vector>

#include "pd_core/polydepth/contact_constraints.h"

namespace pd {

struct MinNormResult {
  Vector3 q = Vector3::Zero();
  int sweeps = 0;
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
