// The in-projection's quadratic program: the shortest q with n_i·q >= c_i.
// References are built from the optimality conditions, not from the solver:
// pick the optimum q* = sum lambda_a n_a (lambda_a > 0) on 1-3 planes, give
// those planes c_a = n_a·q* and every other constraint slack at q*; then q*
// is the unique optimum (KKT conditions of a strictly convex problem).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "pd_core/polydepth/min_norm_point.h"

namespace pd {
namespace {

ContactConstraint Plane(const Vector3& n, double c) {
  ContactConstraint k;
  k.n_S = n.normalized();
  k.c = c;
  return k;
}

Vector3 RandomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Vector3(g(rng), g(rng), g(rng)).normalized();
}

// A problem whose optimum is q*: `active` planes through q* (their normals
// within `spread` radians of each other, so near-parallel for small spread)
// with positive multipliers, and `inactive` constraints slack at q* by
// `slack` (m) or more, shuffled in among them.
struct Problem {
  std::vector<ContactConstraint> constraints;
  Vector3 q_star;
};

Problem MakeProblem(std::mt19937_64& rng, int active, int inactive, double spread,
                    double depth, double slack) {
  std::uniform_real_distribution<double> u(0.2, 1.0);
  const Vector3 axis = RandomUnit(rng);
  std::vector<Vector3> normals;
  Vector3 q_star = Vector3::Zero();
  for (int a = 0; a < active; ++a) {
    const Vector3 n = (axis + spread * RandomUnit(rng)).normalized();
    normals.push_back(n);
    q_star += u(rng) * depth * n;
  }
  Problem p;
  p.q_star = q_star;
  for (const Vector3& n : normals) p.constraints.push_back(Plane(n, n.dot(q_star)));
  for (int j = 0; j < inactive; ++j) {
    const Vector3 n = RandomUnit(rng);
    p.constraints.push_back(Plane(n, n.dot(q_star) - slack * (1.0 + 10.0 * u(rng))));
  }
  std::shuffle(p.constraints.begin(), p.constraints.end(), rng);
  return p;
}

TEST(MinNormPoint, NoConstraintsGiveTheOrigin) {
  MinNormScratch scratch;
  const MinNormResult r = MinNormPoint({}, 1e-6, &scratch);
  EXPECT_EQ(r.q, Vector3::Zero());
  EXPECT_EQ(r.num_unique, 0);
}

TEST(MinNormPoint, ConstraintsSatisfiedAtTheOriginGiveTheOrigin) {
  MinNormScratch scratch;
  const std::vector<ContactConstraint> cs = {Plane({1, 0, 0}, -1e-3), Plane({0, 1, 1}, 0.0)};
  const MinNormResult r = MinNormPoint(cs, 1e-6, &scratch);
  EXPECT_LT(r.q.norm(), 1e-15);
}

// Near-parallel planes (normals 1e-2 to 1e-6 rad apart) are where projected
// Gauss-Seidel crawled: hundreds of sweeps for a handful of constraints,
// stopping short of the optimum. The answer must be q* to round-off, found
// without sweeps.
TEST(MinNormPoint, NearParallelPlanesGiveTheExactOptimum) {
  std::mt19937_64 rng(7);
  MinNormScratch scratch;
  int solved = 0;
  for (double spread : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
    for (int active = 1; active <= 3; ++active) {
      for (int trial = 0; trial < 20; ++trial) {
        const Problem p = MakeProblem(rng, active, 3, spread, 1e-3, 1e-7);
        const MinNormResult r = MinNormPoint(p.constraints, 1e-6, &scratch);
        SCOPED_TRACE(testing::Message() << "spread " << spread << " active " << active
                                        << " trial " << trial);
        // Planes met to stop = 1e-6 tol = 1e-12 m fix q* across their
        // normals only to about stop / spread^2 (they are nearly one plane),
        // but its length and feasibility to that stop.
        EXPECT_NEAR(r.q.norm(), p.q_star.norm(), 1e-12);
        EXPECT_LE(r.max_violation, 1e-12);
        solved += r.sweeps == 0;
      }
    }
  }
  // The exact active-set path, not the sweeps, answers these.
  EXPECT_EQ(solved, 5 * 3 * 20);
}

// Many constraints (a broad contact patch): most slack, 1-3 active planes at
// well-separated angles, so q* itself is fixed to round-off.
TEST(MinNormPoint, ManyConstraintsGiveTheExactOptimum) {
  std::mt19937_64 rng(11);
  MinNormScratch scratch;
  for (int trial = 0; trial < 50; ++trial) {
    const int active = 1 + trial % 3;
    const Problem p = MakeProblem(rng, active, 60, 0.5, 2e-3, 1e-6);
    const MinNormResult r = MinNormPoint(p.constraints, 1e-6, &scratch);
    SCOPED_TRACE(testing::Message() << "trial " << trial);
    EXPECT_LT((r.q - p.q_star).norm(), 1e-14);
    EXPECT_EQ(r.sweeps, 0);
  }
}

// Duplicates of one plane (coplanar contacts) keep the most restrictive.
TEST(MinNormPoint, DuplicatePlanesKeepTheMostRestrictive) {
  MinNormScratch scratch;
  const Vector3 n(0, 0, 1);
  const std::vector<ContactConstraint> cs = {Plane(n, 1e-3), Plane(n, 2e-3), Plane(n, 1.5e-3)};
  const MinNormResult r = MinNormPoint(cs, 1e-6, &scratch);
  EXPECT_EQ(r.num_unique, 1);
  EXPECT_NEAR((r.q - Vector3(0, 0, 2e-3)).norm(), 0.0, 1e-18);
}

// A wedged probe: opposite half-spaces leave no feasible q. The answer is
// finite and reports how far it violates them (the caller rejects it).
TEST(MinNormPoint, InfeasibleConstraintsGiveAFiniteAnswerThatSaysSo) {
  MinNormScratch scratch;
  const std::vector<ContactConstraint> cs = {Plane({1, 0, 0}, 1e-3), Plane({-1, 0, 0}, 1e-3),
                                             Plane({0, 1, 0}, 5e-4)};
  const MinNormResult r = MinNormPoint(cs, 1e-6, &scratch);
  EXPECT_TRUE(r.q.allFinite());
  EXPECT_GT(r.max_violation, 1e-4);
}

}  // namespace
}  // namespace pd
