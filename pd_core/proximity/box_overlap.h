#pragma once
// Separating-axis tests between a probe node box and a scene node box, both
// oriented. Everything is expressed in the scene box's frame B, where the
// scene box is axis-aligned; the probe box A has rotation R_BA and centre
// p_BA there. 15 axes: B's faces, A's faces and the 9 edge-edge products.
#include <algorithm>
#include <cmath>
#include <limits>

#include "pd_core/proximity/bvh.h"
#include "pd_core/proximity/placed_probe_boxes.h"

namespace pd {

// Axis-aligned bounds in S first (three comparisons, no rotation product):
// true if they prove the boxes more than `distance` apart.
inline bool AabbsApart(const ProbeBoxInS& a, const BvhNode& b, double distance) {
  const Vector3 c = (a.p_SA - b.center_M).cwiseAbs();
  return (c.array() > (a.aabb_half_S + b.aabb_half_M.cast<double>()).array() + distance).any();
}

namespace internal {

// Box A relative to the scene box b: R = R_BA, absR = |R_BA| + eps, t = p_BA.
// The rows of R are filled one at a time (Row): a pair that B's first face
// axes already separate never pays for the rest of the rotation product.
struct BoxPair {
  Matrix3 R, absR;
  Vector3 t;
  const Matrix3& R_SA;
  const Matrix3& R_MB;
  const Vector3& ha;
  const Vector3& hb;
  BoxPair(const ProbeBoxInS& a, const BvhNode& b)
      : t(b.R_MB.transpose() * (a.p_SA - b.center_M)),
        R_SA(a.R_SA),
        R_MB(b.R_MB),
        ha(*a.half_A),
        hb(b.half_B) {}
  void Row(int i) {
    R.row(i) = R_MB.col(i).transpose() * R_SA;
    absR.row(i) = R.row(i).cwiseAbs().array() + 1e-12;
  }
};

}  // namespace internal

// Which axes AxisGap looks at.
enum class BoxAxes {
  kFaces,         // the 6 face axes
  kFacesEdges,    // and the 9 edge-edge axes (the 15 separating axes)
  kFacesEdgesCentres,  // and the centres' direction
};

// The one separating-axis routine: the largest gap between the boxes (m)
// along the chosen axes, a lower bound on their distance (<= 0: may
// overlap). Each axis gives |projected centre gap| - radii, divided by the
// axis length. Stops as soon as the bound exceeds `enough` (callers that
// only compare against a threshold pass it: the rest of the axes cannot
// change the answer). With kTrackAxis, *axis_S gets the axis of the largest
// gap (unit, in S, from box b to box a) unless it stopped early.
template <BoxAxes kAxes, bool kTrackAxis = false>
inline double AxisGap(const ProbeBoxInS& a, const BvhNode& b, double enough,
                      Vector3* axis_S = nullptr) {
  internal::BoxPair p(a, b);
  double gap = -1e300;
  // The axis of the largest gap so far, as a code (built once at the end):
  // 0-2 B's face i, 3-5 A's face j, 6-14 edge pair (i, j), 15 centres.
  int best = 0;
  double best_sign = 1.0, best_len = 1.0;
  auto offer = [&](double g, int code, double along, double len) {
    if (g > gap) {
      gap = g;
      if constexpr (kTrackAxis) best = code, best_sign = along, best_len = len;
    }
  };
  for (int i = 0; i < 3; ++i) {
    p.Row(i);
    offer(std::abs(p.t[i]) - p.hb[i] - p.absR.row(i).dot(p.ha), i, p.t[i], 1.0);
    if (gap > enough) return gap;
  }
  for (int j = 0; j < 3; ++j) {
    const double along = p.t.dot(p.R.col(j));
    offer(std::abs(along) - p.absR.col(j).dot(p.hb) - p.ha[j], 3 + j, along, 1.0);
  }
  if (gap > enough) return gap;
  if constexpr (kAxes != BoxAxes::kFaces) {
    for (int i = 0; i < 3; ++i) {
      const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
      for (int j = 0; j < 3; ++j) {
        const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        const double len2 = std::max(0.0, 1.0 - p.R(i, j) * p.R(i, j));
        if (len2 < 1e-12) continue;  // parallel axes: the face axes decide
        // L = e_i x R_j, of length sqrt(len2).
        const double proj = p.t[i2] * p.R(i1, j) - p.t[i1] * p.R(i2, j);
        const double r = p.hb[i1] * p.absR(i2, j) + p.hb[i2] * p.absR(i1, j) +
                         p.ha[j1] * p.absR(i, j2) + p.ha[j2] * p.absR(i, j1);
        // The axis gives (|proj| - r) / len with len <= 1: skip the root
        // where that cannot beat the bound so far (the common case).
        const double d = std::abs(proj) - r;
        if (d <= 0.0 ? d <= gap : (gap > 0.0 && d * d <= gap * gap * len2)) continue;
        const double len = std::sqrt(len2);
        offer(d / len, 6 + 3 * i + j, proj, len);
        if (gap > enough) return gap;
      }
    }
  }
  double t_norm = 0.0;
  if constexpr (kAxes == BoxAxes::kFacesEdgesCentres) {
    t_norm = p.t.norm();
    if (t_norm > 0.0) {
      const Vector3 c = p.t / t_norm;
      offer(t_norm - c.cwiseAbs().dot(p.hb) - (p.R.transpose() * c).cwiseAbs().dot(p.ha), 15,
            1.0, 1.0);
    }
  }
  if constexpr (kTrackAxis) {
    Vector3 axis_B;
    if (best < 3) axis_B = Vector3::Unit(best);
    else if (best < 6) axis_B = p.R.col(best - 3);
    else if (best < 15) axis_B = Vector3::Unit((best - 6) / 3).cross(p.R.col((best - 6) % 3)) / best_len;
    else axis_B = p.t / t_norm;
    if (best_sign < 0.0) axis_B = -axis_B;
    *axis_S = b.R_MB * axis_B;
  }
  return gap;
}

// The 15 separating axes.
inline double BoxGapLowerBound(const ProbeBoxInS& a, const BvhNode& b, double enough = 0.0) {
  return AxisGap<BoxAxes::kFacesEdges>(a, b, enough);
}

// The 15 separating axes and the centres' direction, and the axis of the
// largest gap in *axis_S (unit, in S, from box b to box a): a fixed axis's
// gap is a lower bound on the contents' distance that a later motion
// changes by its component along the axis. Past `enough` it returns at once
// without the axis (a caller that drops such pairs needs neither).
inline double SeparatingAxisGap(const ProbeBoxInS& a, const BvhNode& b, Vector3* axis_S,
                                double enough = std::numeric_limits<double>::infinity()) {
  return AxisGap<BoxAxes::kFacesEdgesCentres, true>(a, b, enough, axis_S);
}

// The bounding spheres' gap (m; a lower bound on the boxes' distance).
inline double SphereGap(const ProbeBoxInS& a, const BvhNode& b) {
  return (a.p_SA - b.center_M).norm() - a.radius - b.radius;
}

// True if the boxes may come within `distance` of each other. The bounding
// spheres of the boxes decide most far pairs for a fraction of the cost of
// the separating axes (no rotation products). When the spheres do not, the
// separating-axis bound is written to *gap_bound if given (a descent key).
template <BoxAxes kAxes = BoxAxes::kFacesEdges>
inline bool BoxesWithin(const ProbeBoxInS& a, const BvhNode& b, double distance,
                        double* gap_bound = nullptr) {
  const double reach = a.radius + b.radius + distance;
  if ((a.p_SA - b.center_M).squaredNorm() > reach * reach) return false;
  if (AabbsApart(a, b, distance)) return false;
  const double gap = AxisGap<kAxes>(a, b, distance);
  if (gap_bound != nullptr) *gap_bound = gap;
  return gap <= distance;
}

// BoxesWithin for a descent: the six face axes on a pair with an internal
// node (kept pairs, most of a descent's tests, then skip the nine edge-edge
// axes; the few extra pairs kept are settled below), all 15 on leaf pairs,
// so the leaf pairs accepted are the same.
inline bool NodesWithin(const ProbeBoxInS& a, const BvhNode& node_a, const BvhNode& b,
                        double distance, double* gap_bound = nullptr) {
  return node_a.is_leaf() && b.is_leaf()
             ? BoxesWithin(a, b, distance, gap_bound)
             : BoxesWithin<BoxAxes::kFaces>(a, b, distance, gap_bound);
}

// The times s in [lo, hi] within [s_min, s_max] at which box A moved by
// s * sweep_S may overlap box b: the bounding spheres must come that near
// within [s_min, s_max], and the axis-aligned bounds in S and, on each of
// the six face axes, the projections must overlap at the same time (the
// nine edge-edge axes would narrow the interval but cost more in the CCD
// than they save). Returns false if that interval is empty. With `grow`
// (m) > 0: the times at which the boxes may come within grow of each other
// (the same tests as BoxesWithin<BoxAxes::kFaces> at each time). The
// divisions are by the sweep's components in S (SweepInS) and along A's
// axes (SweptProbeBoxMemo), computed once, and along B's axes, per pair.
inline bool SweptBoxContactInterval(const SweptProbeBox& sa, const BvhNode& b,
                                    const SweepInS& sweep, double s_max, double* s_lo,
                                    double* s_hi, double grow = 0.0, double s_min = 0.0) {
  const Vector3& sweep_S = sweep.v;
  const ProbeBoxInS& a = sa.box;
  double lo = s_min, hi = s_max;
  const Vector3 c = a.p_SA - b.center_M;
  {
    // Bounding spheres first: |c + s sweep| <= reach, a quadratic in s.
    const double reach = a.radius + b.radius + grow;
    const double qa = sweep.qa, qb = c.dot(sweep_S),
                 qc = c.squaredNorm() - reach * reach;
    if (qa < 1e-300) {
      if (qc > 0) return false;
    } else {
      const double disc = qb * qb - qa * qc;
      if (disc < 0) return false;
      // The quadratic's least value over [lo, hi] (at its vertex, clamped)
      // must not be positive. Its roots would narrow [lo, hi] too, but the
      // boxes' own clips below narrow it about as much, without the root
      // and two divisions (cold queries -2%, same answers).
      const double s_vertex = std::clamp(-qb * sweep.inv_qa, lo, hi);
      if ((qa * s_vertex + 2.0 * qb) * s_vertex + qc > 0) return false;
    }
  }
  auto clip = [&](double center, double rate, double inv, double radius) {
    // |center + s * rate| <= radius, inv = 1 / rate
    if (std::abs(rate) < 1e-300) return std::abs(center) <= radius;
    double t0 = (-radius - center) * inv, t1 = (radius - center) * inv;
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
    return lo <= hi;
  };
  // The axis-aligned bounds in S first (a pair they reject costs no
  // rotation product), then the boxes' face axes.
  const Vector3 r = a.aabb_half_S + b.aabb_half_M.cast<double>();
  for (int i = 0; i < 3; ++i)
    if (!clip(c[i], sweep_S[i], sweep.inv[i], r[i] + grow)) return false;
  internal::BoxPair p(a, b);
  const Vector3 d = b.R_MB.transpose() * sweep_S;  // sweep in B
  const Vector3 inv_d = d.cwiseInverse();
  for (int i = 0; i < 3; ++i) {
    p.Row(i);
    if (!clip(p.t[i], d[i], inv_d[i], p.hb[i] + p.absR.row(i).dot(p.ha) + grow)) return false;
  }
  for (int j = 0; j < 3; ++j)
    if (!clip(p.t.dot(p.R.col(j)), sa.rate_A[j], sa.inv_rate_A[j],
              p.absR.col(j).dot(p.hb) + p.ha[j] + grow))
      return false;
  *s_lo = lo;
  *s_hi = hi;
  return true;
}

}  // namespace pd
