#include "pd_core/convex/convex_pd.h"

#include <algorithm>
#include <cmath>

#include "pd_core/geometry/fibonacci_sphere.h"

namespace pd {

namespace {

double PairSize(const Geometry& a, const Geometry& b) { return a.radius() + b.radius(); }

// Smallest full support value h(n) = h_S(n) + h_P(-n) over directions near
// `n0`: Fibonacci directions, then a pattern search with a shrinking step.
void SamplingSearch(const MinkowskiDifference& D, int num_directions, Vector3* n_best,
                    double* h_best) {
  auto consider = [&](const Vector3& n) {
    const double h = D.FullSupportValue(n);
    if (h < *h_best) *h_best = h, *n_best = n;
  };
  for (int i = 0; i < num_directions; ++i) consider(FibonacciDirection(i, num_directions));
  double step = 0.3;
  for (int it = 0; it < 60 && step > 1e-9; ++it) {
    const Vector3 n0 = *n_best;
    const Vector3 e1 = n0.unitOrthogonal(), e2 = n0.cross(e1);
    const double before = *h_best;
    for (int k = 0; k < 4; ++k) {
      const double a = M_PI / 2 * k;
      consider((n0 + step * (std::cos(a) * e1 + std::sin(a) * e2)).normalized());
    }
    if (*h_best >= before) step *= 0.5;
  }
}

}  // namespace

PairPdAnswer ConvexPenetrationDepth(const Geometry& probe, const Isometry3& X_WP,
                                    const Geometry& scene, const Isometry3& X_WS,
                                    const ConvexPdOptions& options, const Vector3& guess_W,
                                    EpaScratch* scratch) {
  const MinkowskiDifference D{&probe, &scene, X_WP, X_WS};
  const double size = PairSize(probe, scene);
  const double tol = options.rel_tol * size;
  const double margin = D.margin();
  Vector3 guess = guess_W;
  if (guess.squaredNorm() == 0.0)
    guess = (X_WS * scene.center()) - (X_WP * probe.center());
  PairPdAnswer answer;
  const GjkResult gjk = Gjk(D, guess, tol, 1e-12, options.max_gjk_iterations);
  answer.iterations = gjk.iterations;
  Vector3 n;
  if (!gjk.intersecting) {
    // Cores apart: PD is margin - distance along -v (if positive).
    n = -gjk.v.normalized();
    if (margin <= 0.0 || -n.dot(gjk.w) >= margin) return answer;  // quick reject
  } else {
    const EpaResult epa = Epa(D, gjk.simplex, tol, options.max_epa_iterations, scratch);
    answer.iterations += epa.iterations;
    n = epa.normal_W;
    if (!epa.converged) {
      answer.converged = false;
      double h = D.FullSupportValue(n);
      SamplingSearch(D, options.num_fallback_directions, &n, &h);
    }
  }
  const double depth = D.FullSupportValue(n);
  if (!(depth > 0.0)) return answer;
  answer.in_collision = true;
  answer.depth = depth;
  answer.normal_W = n;
  return answer;
}

double ConvexDistance(const Geometry& a, const Isometry3& X_WA, const Geometry& b,
                      const Isometry3& X_WB) {
  const MinkowskiDifference D{&a, &b, X_WA, X_WB};
  const double tol = 1e-13 * PairSize(a, b);
  const GjkResult gjk = Gjk(D, X_WB * b.center() - X_WA * a.center(), tol, 1e-10, 256);
  if (gjk.intersecting) return -std::max(D.margin(), tol);
  return gjk.v.norm() - D.margin();
}

}  // namespace pd
