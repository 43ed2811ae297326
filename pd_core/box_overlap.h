#pragma once
// Separating-axis tests between a probe node box (axis-aligned in P, so an
// oriented box in S) and a scene node box (axis-aligned in S). The probe box
// may be inflated by a margin and swept along a translation.
#include <algorithm>
#include <cmath>

#include "pd_core/bvh.h"
#include "pd_core/relative_pose.h"

namespace pd {

// Probe box expressed in S: centre, rotation columns, and the extents of its
// projection on S's axes.
struct ProbeBoxInS {
  Vector3 center_S;
  Vector3 extent_on_S_axes;  // |R| * half
  const Vector3* half_P;
};

inline ProbeBoxInS ProbeBox(const BvhNode& node, const RelativePose& X_SP,
                            const Vector3& offset_S) {
  return {X_SP * node.center_M + offset_S, X_SP.absR_SP * node.half_M, &node.half_M};
}

// Lower bound on the distance between the probe box moved over the segment
// [0, sweep_S] and the scene box; <= margin means "may be within margin".
// Uses S's axes, P's axes and, for a sweep, the cross products sweep x S-axes.
inline double BoxGapLowerBound(const ProbeBoxInS& a, const BvhNode& b,
                               const RelativePose& X_SP, const Vector3& sweep_S) {
  const Vector3 c = a.center_S + 0.5 * sweep_S - b.center_M;
  const Vector3 half_sweep = 0.5 * sweep_S.cwiseAbs();
  // S axes.
  const Vector3 gap_s = c.cwiseAbs() - a.extent_on_S_axes - b.half_M - half_sweep;
  double gap = gap_s.maxCoeff();
  if (gap > 0) return gap;
  // P axes: L = column j of R_SP.
  for (int j = 0; j < 3; ++j) {
    const double proj_c = std::abs(X_SP.R_SP.col(j).dot(c));
    const double r_b = X_SP.absR_SP.col(j).dot(b.half_M);
    const double r_s = 0.5 * std::abs(X_SP.R_SP.col(j).dot(sweep_S));
    gap = std::max(gap, proj_c - (*a.half_P)[j] - r_b - r_s);
  }
  if (gap > 0 || sweep_S.isZero()) return gap;
  // sweep x e_k for S's axes (the swept box's side faces).
  for (int k = 0; k < 3; ++k) {
    Vector3 L = sweep_S.cross(Vector3::Unit(k));
    const double len = L.norm();
    if (len < 1e-12 * sweep_S.norm()) continue;
    L /= len;
    const double proj_c = std::abs(L.dot(c));
    const double r_a = (X_SP.R_SP.transpose() * L).cwiseAbs().dot(*a.half_P);
    const double r_b = L.cwiseAbs().dot(b.half_M);
    gap = std::max(gap, proj_c - r_a - r_b);  // L is orthogonal to the sweep
  }
  return gap;
}

}  // namespace pd

namespace pd {

// The times s in [s_lo, s_hi] at which the probe box moved by s * sweep_S can
// overlap the scene box, from the slab overlap on S's and P's axes (a
// projection overlap must hold on every axis at the same time). Returns false
// if the interval within [0, s_max] is empty.
inline bool SweptBoxContactInterval(const ProbeBoxInS& a, const BvhNode& b,
                                    const RelativePose& X_SP, const Vector3& sweep_S,
                                    double s_max, double* s_lo, double* s_hi) {
  double lo = 0.0, hi = s_max;
  const Vector3 c = a.center_S - b.center_M;
  auto clip = [&](double center, double rate, double radius) {
    // |center + s*rate| <= radius
    if (std::abs(rate) < 1e-300) return std::abs(center) <= radius;
    double t0 = (-radius - center) / rate, t1 = (radius - center) / rate;
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
    return lo <= hi;
  };
  for (int k = 0; k < 3; ++k)
    if (!clip(c[k], sweep_S[k], a.extent_on_S_axes[k] + b.half_M[k])) return false;
  for (int j = 0; j < 3; ++j) {
    const Vector3 L = X_SP.R_SP.col(j);
    if (!clip(L.dot(c), L.dot(sweep_S), (*a.half_P)[j] + X_SP.absR_SP.col(j).dot(b.half_M)))
      return false;
  }
  // Edge-edge axes e_k x R_j: they separate thin, rotated boxes that the face
  // axes cannot, which matters for long sliver triangles.
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      // L = e_k x R_col_j, expressed in S: components of the cross product.
      Vector3 L = Vector3::Unit(k).cross(X_SP.R_SP.col(j));
      const double len2 = L.squaredNorm();
      if (len2 < 1e-12) continue;
      const double r_b = b.half_M[k1] * X_SP.absR_SP(k2, j) + b.half_M[k2] * X_SP.absR_SP(k1, j);
      const double r_a = (*a.half_P)[j1] * X_SP.absR_SP(k, j2) + (*a.half_P)[j2] * X_SP.absR_SP(k, j1);
      if (!clip(L.dot(c), L.dot(sweep_S), r_a + r_b)) return false;
    }
  }
  *s_lo = lo;
  *s_hi = hi;
  return true;
}

}  // namespace pd
