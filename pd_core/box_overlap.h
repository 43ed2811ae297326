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
