// Node-pair tests (pd_core/proximity/box_overlap.h) and the placed probe
// boxes they take (placed_probe_boxes.h), over random boxes, rotations and
// distances: the boxes' axis-aligned bounds in the scene frame S call a pair
// apart exactly when bounds built here from the boxes' 8 corners are apart;
// the per-query cache of placed boxes gives ProbeBox's boxes; the swept
// test keeps every time at which the 15 separating axes find the boxes
// overlapping.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

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

// The per-query table of placed probe boxes (placed_probe_boxes.h) gives
// ProbeBox's boxes bit for bit, at any translation, for nodes that share a
// slot, and after Invalidate the new pose's boxes, never the old ones.
TEST(BoxOverlap, ProbeBoxCacheGivesProbeBoxsBoxesAndForgetsAnOldPose) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> c(-1.0, 1.0);
  std::vector<BvhNode> nodes;
  for (int k = 0; k < 3000; ++k) nodes.push_back(RandomBox(rng));  // 3 nodes per slot
  auto cache = std::make_unique<ProbeBoxCache>();
  for (int pose = 0; pose < 3; ++pose) {
    RelativePose X_SP;
    X_SP.R_SP = RandomRotation(rng);
    X_SP.p_SP = Vector3(c(rng), c(rng), c(rng));
    X_SP.absR_SP = X_SP.R_SP.cwiseAbs().array() + 1e-12;
    cache->Invalidate();
    for (int k = 0; k < 20000; ++k) {
      const int32_t index = std::uniform_int_distribution<int32_t>(0, 2999)(rng);
      const Vector3 offset_S(c(rng), c(rng), c(rng));
      const ProbeBoxInS got = cache->Get(nodes[index], index, X_SP, offset_S);
      const ProbeBoxInS want = ProbeBox(nodes[index], X_SP, offset_S);
      ASSERT_TRUE(got.R_SA == want.R_SA) << "pose " << pose << " node " << index;
      ASSERT_TRUE(got.p_SA == want.p_SA) << "pose " << pose << " node " << index;
      ASSERT_TRUE(got.aabb_half_S == want.aabb_half_S) << "pose " << pose << " node " << index;
      ASSERT_EQ(got.half_A, want.half_A);
      ASSERT_EQ(got.radius, want.radius);
    }
  }
}

// The swept test never drops a time at which the boxes overlap: at sampled
// times s the boxes moved by s * sweep overlap by the 15 separating axes
// (exact for boxes), and there the swept test must keep the pair with s in
// its interval. Random boxes, rotations and sweeps, some along an axis (a
// zero component of the sweep) and some of zero length.
TEST(BoxOverlap, SweptIntervalHoldsEveryTimeTheBoxesOverlap) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> c(-1.0, 1.0);
  int overlapping_times = 0, rejected = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const BvhNode node_a = RandomBox(rng), b = RandomBox(rng);
    RelativePose X_SP;
    X_SP.R_SP = RandomRotation(rng);
    X_SP.p_SP = Vector3(c(rng), c(rng), c(rng));
    X_SP.absR_SP = X_SP.R_SP.cwiseAbs().array() + 1e-12;
    Vector3 sweep_S = 4.0 * Vector3(c(rng), c(rng), c(rng));
    if (trial % 5 == 1) sweep_S.y() = 0.0;
    if (trial % 50 == 2) sweep_S.setZero();
    const Vector3 offset_S = -0.5 * sweep_S;
    const SweepInS sweep(sweep_S);
    SweptProbeBoxMemo memo(X_SP, offset_S, sweep);
    const double s_min = trial % 3 == 0 ? 0.25 : 0.0, s_max = trial % 4 == 0 ? 0.7 : 1.0;
    double lo = 0, hi = 0;
    const bool kept = SweptBoxContactInterval(memo(node_a), b, sweep, s_max, &lo, &hi, 0.0, s_min);
    rejected += !kept;
    for (int k = 0; k <= 200; ++k) {
      const double s = s_min + (s_max - s_min) * k / 200.0;
      const ProbeBoxInS a = ProbeBox(node_a, X_SP, offset_S + s * sweep_S);
      if (BoxGapLowerBound(a, b) > -1e-9) continue;  // apart, or too near to call
      ++overlapping_times;
      ASSERT_TRUE(kept) << "trial " << trial << " overlap at s = " << s;
      EXPECT_LE(lo, s + 1e-9) << "trial " << trial;
      EXPECT_GE(hi, s - 1e-9) << "trial " << trial;
    }
  }
  EXPECT_GT(overlapping_times, 20000);
  EXPECT_GT(rejected, 300);  // the test does reject pairs
}

}  // namespace
}  // namespace pd
