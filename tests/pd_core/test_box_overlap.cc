// The first test of a node pair (pd_core/proximity/box_overlap.h): the
// boxes' axis-aligned bounds in the scene frame S. A pair it calls apart
// must be apart; checked against bounds built here from the boxes' 8
// corners, over random boxes, rotations and distances.
#include <gtest/gtest.h>

#include <random>

#include "pd_core/proximity/box_overlap.h"

namespace pd {
namespace {

Matrix3 RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

BvhNode RandomBox(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.01, 1.0), c(-1.5, 1.5);
  BvhNode n;
  n.R_MB = RandomRotation(rng);
  n.center_M = Vector3(c(rng), c(rng), c(rng));
  n.half_B = Vector3(u(rng), u(rng), 0.1 * u(rng));  // flat, like a leaf's box
  std::vector<BvhNode> one{n};
  Bvh::DeriveBounds(&one);
  return one[0];
}

// Lowest and highest corner of a box (axes R, centre p, half extents h), per axis.
void CornerBounds(const Matrix3& R, const Vector3& p, const Vector3& h, Vector3* lo, Vector3* hi) {
  *lo = Vector3::Constant(1e300);
  *hi = Vector3::Constant(-1e300);
  for (int k = 0; k < 8; ++k) {
    const Vector3 corner = p + R * Vector3((k & 1 ? 1 : -1) * h.x(), (k & 2 ? 1 : -1) * h.y(),
                                           (k & 4 ? 1 : -1) * h.z());
    *lo = lo->cwiseMin(corner);
    *hi = hi->cwiseMax(corner);
  }
}

TEST(BoxOverlap, AxisAlignedBoundsCallAPairApartExactlyWhenTheirCornersAreApart) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> dist(0.0, 0.3);
  int apart = 0, near = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const BvhNode node_a = RandomBox(rng), b = RandomBox(rng);
    RelativePose X_SP;
    X_SP.R_SP = RandomRotation(rng);
    X_SP.p_SP = Vector3(0.1, -0.2, 0.3);
    X_SP.absR_SP = X_SP.R_SP.cwiseAbs().array() + 1e-12;
    const Vector3 offset_S(0.05, 0.0, -0.1);
    const ProbeBoxInS a = ProbeBox(node_a, X_SP, offset_S);
    const double distance = trial % 2 ? dist(rng) : 0.0;
    Vector3 lo_a, hi_a, lo_b, hi_b;
    CornerBounds(X_SP.R_SP * node_a.R_MB, X_SP * node_a.center_M + offset_S, node_a.half_B, &lo_a,
                 &hi_a);
    CornerBounds(b.R_MB, b.center_M, b.half_B, &lo_b, &hi_b);
    const double gap = std::max((lo_a - hi_b).maxCoeff(), (lo_b - hi_a).maxCoeff());
    // Away from the boundary (the scene box's bounds are floats rounded up:
    // ~1e-7 of these boxes' size), the two must agree.
    if (std::abs(gap - distance) < 1e-6) continue;
    const bool expected = gap > distance;
    EXPECT_EQ(AabbsApart(a, b, distance), expected) << "trial " << trial << " gap " << gap;
    if (expected) {
      ++apart;
      // Apart by the bounds: apart by the exact 15-axis test too.
      EXPECT_GT(BoxGapLowerBound(a, b), 0.0) << "trial " << trial;
      EXPECT_FALSE(BoxesWithin(a, b, distance)) << "trial " << trial;
    } else {
      ++near;
    }
  }
  // Both verdicts were exercised.
  EXPECT_GT(apart, 500);
  EXPECT_GT(near, 500);
}

}  // namespace
}  // namespace pd
