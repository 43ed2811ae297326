#include "pd_core/polydepth/min_norm_point.h"

#include <Eigen/Dense>
#include <cmath>

namespace pd {

MinNormResult MinNormPoint(const std::vector<ContactConstraint>& constraints, double tol,
                           MinNormScratch* scratch, int max_sweeps) {
  MinNormResult result;
  auto& unique = scratch->unique;
  unique.clear();
  // Merge duplicate normals (coplanar contacts report the same plane many
  // times): keep the most restrictive offset of each direction.
  for (int i = 0; i < static_cast<int>(constraints.size()); ++i) {
    const ContactConstraint& ci = constraints[i];
    bool merged = false;
    for (int& u : unique) {
      const ContactConstraint& cu = constraints[u];
      if (ci.n_S.dot(cu.n_S) > 1.0 - 1e-12) {
        if (ci.c > cu.c) u = i;
        merged = true;
        break;
      }
    }
    if (!merged) unique.push_back(i);
  }
  const int m = static_cast<int>(unique.size());
  result.num_unique = m;
  if (m == 0) return result;

  auto& lambda = scratch->lambda;
  lambda.assign(m, 0.0);
  Vector3 q = Vector3::Zero();
  const double stop = 1e-6 * tol;
  int sweep = 0;
  for (; sweep < max_sweeps; ++sweep) {
    double max_step = 0.0;
    for (int k = 0; k < m; ++k) {
      const ContactConstraint& c = constraints[unique[k]];
      const double step = std::max(-lambda[k], c.c - c.n_S.dot(q));
      lambda[k] += step;
      q += step * c.n_S;
      max_step = std::max(max_step, std::abs(step));
    }
    if (max_step <= stop) break;
  }
  result.sweeps = sweep + 1;

  // Polish: the optimum is fixed by at most three active planes in 3D.
  int active[3], na = 0;
  bool small = true;
  for (int k = 0; k < m; ++k) {
    if (lambda[k] > 0) {
      if (na == 3) {
        small = false;
        break;
      }
      active[na++] = k;
    }
  }
  if (small && na > 0) {
    Eigen::Matrix3d G = Eigen::Matrix3d::Identity();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (int a = 0; a < na; ++a) {
      rhs[a] = constraints[unique[active[a]]].c;
      for (int b = 0; b < na; ++b)
        G(a, b) = constraints[unique[active[a]]].n_S.dot(constraints[unique[active[b]]].n_S);
    }
    // Unused rows stay identity with zero right-hand side: lambda = 0 there,
    // so one fixed-size solve covers 1 to 3 active planes without allocation.
    const Eigen::Vector3d lam = G.ldlt().solve(rhs);
    bool ok = lam.allFinite() && (lam.array() >= 0).all();
    if (ok) {
      Vector3 q_exact = Vector3::Zero();
      for (int a = 0; a < na; ++a) q_exact += lam[a] * constraints[unique[active[a]]].n_S;
      double viol = 0.0;
      for (int k = 0; k < m; ++k) {
        const ContactConstraint& c = constraints[unique[k]];
        viol = std::max(viol, c.c - c.n_S.dot(q_exact));
      }
      if (viol <= stop) q = q_exact;
    }
  }
  double viol = 0.0;
  for (int k = 0; k < m; ++k) {
    const ContactConstraint& c = constraints[unique[k]];
    viol = std::max(viol, c.c - c.n_S.dot(q));
  }
  result.q = q;
  result.max_violation = viol;
  return result;
}

}  // namespace pd
