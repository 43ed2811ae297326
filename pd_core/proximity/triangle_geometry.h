#pragma once
// Exact-as-doubles primitives on triangles and segments used by the BVH
// queries. All points are in one common frame; units are metres.
#include <algorithm>
#include <cmath>

#include "pd_core/geometry/pose.h"

namespace pd {

// True if triangle v[0..2] lies wholly on one side of the plane through o
// with unit normal n, farther than `gap` from it, and stays so while it moves
// along n by any amount between 0 and `move` (m; 0 for a static test): then
// no point of it comes within `gap` of anything in that plane. A zero n
// (degenerate triangle) never decides.
inline bool TriangleStaysOffPlane(const Vector3& n, const Vector3& o, const Vector3* v,
                                  double move, double gap) {
  double lo = 1e300, hi = -1e300;
  for (int k = 0; k < 3; ++k) {
    const double h = n.dot(v[k] - o);
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  return lo + std::min(0.0, move) > gap || hi + std::max(0.0, move) < -gap;
}

// True if the closed triangles intersect (touching counts), by the separating
// axis theorem over both normals, the 9 edge-edge cross products and the 6
// in-plane edge normals (which decide the coplanar case).
inline bool TrianglesIntersect(const Vector3& a0, const Vector3& a1, const Vector3& a2,
                               const Vector3& b0, const Vector3& b1, const Vector3& b2) {
  const Vector3 ea[3] = {a1 - a0, a2 - a1, a0 - a2};
  const Vector3 eb[3] = {b1 - b0, b2 - b1, b0 - b2};
  const Vector3 na = ea[0].cross(ea[1]);
  const Vector3 nb = eb[0].cross(eb[1]);
  auto separated = [&](const Vector3& L) {
    const double pa0 = L.dot(a0), pa1 = L.dot(a1), pa2 = L.dot(a2);
    const double pb0 = L.dot(b0), pb1 = L.dot(b1), pb2 = L.dot(b2);
    const double amin = std::min({pa0, pa1, pa2}), amax = std::max({pa0, pa1, pa2});
    const double bmin = std::min({pb0, pb1, pb2}), bmax = std::max({pb0, pb1, pb2});
    return amax < bmin || bmax < amin;
  };
  // Plane tests first: most non-intersecting pairs fail here cheaply.
  if (separated(na) || separated(nb)) return false;
  const double scale2 = std::max(na.squaredNorm(), nb.squaredNorm());
  bool any_cross = false;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Vector3 L = ea[i].cross(eb[j]);
      if (L.squaredNorm() <= 1e-24 * ea[i].squaredNorm() * eb[j].squaredNorm()) continue;
      any_cross = true;
      if (separated(L)) return false;
    }
  }
  (void)scale2;
  // Near-coplanar (or parallel-edged) pairs: in-plane edge normals decide.
  for (int i = 0; i < 3; ++i) {
    if (separated(na.cross(ea[i]))) return false;
    if (separated(nb.cross(eb[i]))) return false;
  }
  (void)any_cross;
  return true;
}

// Barycentric-clamped closest point on triangle (a, b, c) to p (Ericson 5.1.5).
inline Vector3 ClosestPointOnTriangle(const Vector3& p, const Vector3& a, const Vector3& b,
                                      const Vector3& c) {
  const Vector3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vector3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vector3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Closest points between segments p0p1 and q0q1 (Ericson 5.1.9). Returns the
// squared distance; s, t are the parameters of the closest points.
inline double ClosestSegmentSegment(const Vector3& p0, const Vector3& p1, const Vector3& q0,
                                    const Vector3& q1, double* s_out, double* t_out,
                                    Vector3* cp, Vector3* cq) {
  const Vector3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  const double tiny = 1e-30;
  if (a <= tiny && e <= tiny) {
    s = t = 0;
  } else if (a <= tiny) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= tiny) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;
      s = denom > 1e-14 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  *s_out = s;
  *t_out = t;
  *cp = p0 + d1 * s;
  *cq = q0 + d2 * t;
  return (*cp - *cq).squaredNorm();
}

// Ray o + s*d against triangle (a, b, c), both sides. Returns the smallest
// s in [0, s_max] with a hit (barycentric tolerance `bary_tol` on edges), or
// a negative value if none. Möller-Trumbore.
inline double RayTriangle(const Vector3& o, const Vector3& d, const Vector3& a,
                          const Vector3& b, const Vector3& c, double s_max,
                          double bary_tol = 1e-12) {
  const Vector3 e1 = b - a, e2 = c - a;
  const Vector3 pv = d.cross(e2);
  const double det = e1.dot(pv);
  if (std::abs(det) <= 1e-300) return -1.0;
  const double inv = 1.0 / det;
  const Vector3 tv = o - a;
  const double u = tv.dot(pv) * inv;
  if (u < -bary_tol || u > 1 + bary_tol) return -1.0;
  const Vector3 qv = tv.cross(e1);
  const double v = d.dot(qv) * inv;
  if (v < -bary_tol || u + v > 1 + bary_tol) return -1.0;
  const double s = e2.dot(qv) * inv;
  if (s < 0 || s > s_max) return -1.0;
  return s;
}

// Segment p0p1 translated by s*d first touching segment q0q1: solves
// p0 + u (p1-p0) + s d = q0 + v (q1-q0) for u, v in [0,1]. Returns s in
// [0, s_max] or a negative value when they never cross (or are coplanar with
// d, in which case vertex-face events find the contact).
inline double EdgeEdgeTranslationalContact(const Vector3& p0, const Vector3& p1,
                                           const Vector3& q0, const Vector3& q1,
                                           const Vector3& d, double s_max) {
  const Vector3 e = p1 - p0, f = q1 - q0, r = q0 - p0;
  // u e - v f + s d = r.  Cramer's rule with columns (e, -f, d).
  const Vector3 fxd = f.cross(d);
  const double det = -e.dot(fxd);  // det[e, -f, d] = e · (-f x d)
  const double scale = e.norm() * f.norm() * d.norm();
  if (std::abs(det) <= 1e-12 * scale) return -1.0;
  const double inv = 1.0 / det;
  const double s = e.dot(-f.cross(r)) * inv;  // det[e, -f, r]
  if (s < 0 || s > s_max) return -1.0;
  const double u = r.dot(-fxd) * inv;  // det[r, -f, d]
  if (u < 0 || u > 1) return -1.0;
  const double v = e.dot(r.cross(d)) * inv;  // det[e, r, d]
  if (v < 0 || v > 1) return -1.0;
  return s;
}

}  // namespace pd
