#include "pd_core/convex/gjk.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pd {

namespace {

void ClosestOnSegment(GjkSimplex* s, Vector3* v) {
  const Vector3 a = s->points[0], b = s->points[1];
  const Vector3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? -a.dot(ab) / len2 : 0.0;
  if (t <= 0.0) {
    s->size = 1;
    *v = a;
  } else if (t >= 1.0) {
    s->points[0] = b;
    s->size = 1;
    *v = b;
  } else {
    *v = a + t * ab;
  }
}

// Ericson, Real-Time Collision Detection 5.1.5, with the query point at the
// origin; keeps the vertices of the closest feature.
void ClosestOnTriangle(GjkSimplex* s, Vector3* v) {
  const Vector3 a = s->points[0], b = s->points[1], c = s->points[2];
  const Vector3 ab = b - a, ac = c - a;
  const double d1 = -ab.dot(a), d2 = -ac.dot(a);
  auto set = [&](std::initializer_list<Vector3> pts, const Vector3& p) {
    int i = 0;
    for (const Vector3& q : pts) s->points[i++] = q;
    s->size = i;
    *v = p;
  };
  if (d1 <= 0 && d2 <= 0) return set({a}, a);
  const double d3 = -ab.dot(b), d4 = -ac.dot(b);
  if (d3 >= 0 && d4 <= d3) return set({b}, b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return set({a, b}, a + d1 / (d1 - d3) * ab);
  const double d5 = -ab.dot(c), d6 = -ac.dot(c);
  if (d6 >= 0 && d5 <= d6) return set({c}, c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return set({a, c}, a + d2 / (d2 - d6) * ac);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return set({b, c}, b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b));
  const double sum = va + vb + vc;
  if (!(std::abs(sum) > 0.0)) {  // degenerate (collinear) triangle: best edge
    GjkSimplex e1{{a, b}, 2}, e2{{b, c}, 2}, e3{{a, c}, 2};
    Vector3 v1, v2, v3;
    ClosestOnSegment(&e1, &v1), ClosestOnSegment(&e2, &v2), ClosestOnSegment(&e3, &v3);
    GjkSimplex* best = &e1;
    Vector3 bv = v1;
    if (v2.squaredNorm() < bv.squaredNorm()) best = &e2, bv = v2;
    if (v3.squaredNorm() < bv.squaredNorm()) best = &e3, bv = v3;
    *s = *best;
    *v = bv;
    return;
  }
  *v = a + (vb / sum) * ab + (vc / sum) * ac;
}

// Is the origin on the other side of plane (a, b, c) from d? Degenerate
// (flat) configurations count as outside so the face gets tested.
bool OriginOutsideFace(const Vector3& a, const Vector3& b, const Vector3& c, const Vector3& d) {
  const Vector3 n = (b - a).cross(c - a);
  const double sign_o = -a.dot(n);
  const double sign_d = (d - a).dot(n);
  return sign_d == 0.0 || sign_o * sign_d < 0.0;
}

bool ClosestOnTetrahedron(GjkSimplex* s, Vector3* v) {
  const std::array<Vector3, 4> p = s->points;
  static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
  // A nearly flat tetrahedron makes the side tests unreliable (it could
  // claim to hold an origin lying off its plane): test all faces then.
  double scale = 0.0;
  for (int i = 1; i < 4; ++i) scale = std::max(scale, (p[i] - p[0]).norm());
  const double volume6 = (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]));
  const bool flat = std::abs(volume6) <= 1e-9 * scale * scale * scale;
  double best = std::numeric_limits<double>::infinity();
  bool outside_any = false;
  GjkSimplex best_s;
  for (const auto& f : kFaces) {
    if (!flat && !OriginOutsideFace(p[f[0]], p[f[1]], p[f[2]], p[f[3]])) continue;
    outside_any = true;
    GjkSimplex t{{p[f[0]], p[f[1]], p[f[2]]}, 3};
    Vector3 q;
    ClosestOnTriangle(&t, &q);
    if (q.squaredNorm() < best) best = q.squaredNorm(), best_s = t, *v = q;
  }
  if (!outside_any) {
    *v = Vector3::Zero();
    return false;
  }
  *s = best_s;
  return true;
}

}  // namespace

bool ClosestPointOnSimplex(GjkSimplex* simplex, Vector3* v) {
  switch (simplex->size) {
    case 1: *v = simplex->points[0]; return true;
    case 2: ClosestOnSegment(simplex, v); return true;
    case 3: ClosestOnTriangle(simplex, v); return true;
    default: return ClosestOnTetrahedron(simplex, v);
  }
}

GjkResult Gjk(const MinkowskiDifference& D, const Vector3& guess_W, double tol_abs,
              double rel_tol, int max_iterations) {
  GjkResult r;
  const Vector3 d0 = guess_W.squaredNorm() > 0.0 ? guess_W : Vector3::UnitX();
  r.v = D.Support(d0);
  r.simplex.points[0] = r.v;
  r.simplex.size = 1;
  const double tol2 = tol_abs * tol_abs;
  for (r.iterations = 1; r.iterations <= max_iterations; ++r.iterations) {
    const double vv = r.v.squaredNorm();
    if (vv <= tol2) {
      r.intersecting = true;
      return r;
    }
    r.w = D.Support(-r.v);
    // Upper bound |v|, lower bound v̂·w: stop when they meet.
    if (vv - r.v.dot(r.w) <= rel_tol * vv + tol_abs * std::sqrt(vv)) return r;
    bool duplicate = false;
    for (int i = 0; i < r.simplex.size; ++i)
      if ((r.simplex.points[i] - r.w).squaredNorm() <= tol2) duplicate = true;
    if (duplicate) return r;
    r.simplex.points[r.simplex.size++] = r.w;
    Vector3 v;
    if (!ClosestPointOnSimplex(&r.simplex, &v)) {
      r.v = Vector3::Zero();
      r.intersecting = true;
      return r;
    }
    if (v.squaredNorm() >= vv) return r;  // no progress: numerically converged
    r.v = v;
  }
  r.w = D.Support(-r.v);
  return r;
}

}  // namespace pd
