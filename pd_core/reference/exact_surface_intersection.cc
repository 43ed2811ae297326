#include "pd_core/reference/exact_surface_intersection.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "pd_core/reference/sweep_pairs.h"

namespace pd {
namespace reference {
namespace {

// Triangle-triangle intersection for the collision test (closed triangles).
// Orientation signs decide everything; they are recomputed in quad precision
// when the double result is within its rounding error bound, so a segment
// sliding exactly in a triangle's plane is not misjudged.

#if defined(__SIZEOF_FLOAT128__)
using Wide = __float128;
#else
using Wide = long double;  // quad precision where long double is (e.g. aarch64)
#endif

struct P2 {
  double x, y;
};

// (b - a) x (c - a), sign exact up to quad-precision rounding.
double Orient2(const P2& a, const P2& b, const P2& c) {
  const double bx = b.x - a.x, by = b.y - a.y, cx = c.x - a.x, cy = c.y - a.y;
  const double det = bx * cy - by * cx;
  if (std::abs(det) > 1e-15 * (std::abs(bx * cy) + std::abs(by * cx))) return det;
  const Wide wbx = Wide(b.x) - Wide(a.x), wby = Wide(b.y) - Wide(a.y);
  const Wide wcx = Wide(c.x) - Wide(a.x), wcy = Wide(c.y) - Wide(a.y);
  return static_cast<double>(wbx * wcy - wby * wcx);
}

// (b - a) x (c - a) . (d - a), sign exact up to quad-precision rounding.
double Orient3(const Vector3& a, const Vector3& b, const Vector3& c, const Vector3& d) {
  const Vector3 ba = b - a, ca = c - a, da = d - a;
  const double m0 = ca.y() * da.z(), m1 = ca.z() * da.y();
  const double m2 = ca.z() * da.x(), m3 = ca.x() * da.z();
  const double m4 = ca.x() * da.y(), m5 = ca.y() * da.x();
  const double det = ba.x() * (m0 - m1) + ba.y() * (m2 - m3) + ba.z() * (m4 - m5);
  const double permanent = std::abs(ba.x()) * (std::abs(m0) + std::abs(m1)) +
                           std::abs(ba.y()) * (std::abs(m2) + std::abs(m3)) +
                           std::abs(ba.z()) * (std::abs(m4) + std::abs(m5));
  if (std::abs(det) > 1e-15 * permanent) return det;
  Wide w[3][3];
  for (int i = 0; i < 3; ++i) {
    w[0][i] = Wide(b[i]) - Wide(a[i]);
    w[1][i] = Wide(c[i]) - Wide(a[i]);
    w[2][i] = Wide(d[i]) - Wide(a[i]);
  }
  const Wide wdet = w[0][0] * (w[1][1] * w[2][2] - w[1][2] * w[2][1]) +
                    w[0][1] * (w[1][2] * w[2][0] - w[1][0] * w[2][2]) +
                    w[0][2] * (w[1][0] * w[2][1] - w[1][1] * w[2][0]);
  return static_cast<double>(wdet);
}

// c is collinear with a-b: is it within the segment?
inline bool WithinBox2(const P2& a, const P2& b, const P2& c) {
  return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
         c.y <= std::max(a.y, b.y);
}

bool SegmentsIntersect2(const P2& a, const P2& b, const P2& c, const P2& d) {
  const double o1 = Orient2(a, b, c), o2 = Orient2(a, b, d);
  const double o3 = Orient2(c, d, a), o4 = Orient2(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
    return true;
  return (o1 == 0 && WithinBox2(a, b, c)) || (o2 == 0 && WithinBox2(a, b, d)) ||
         (o3 == 0 && WithinBox2(c, d, a)) || (o4 == 0 && WithinBox2(c, d, b));
}

// Segment p-q lying in the plane of triangle t (normal n): do they meet?
// Dropping the normal's largest axis projects without degenerating.
bool CoplanarSegmentHitsTriangle(const Vector3& p, const Vector3& q, const Vector3* t,
                                 const Vector3& n) {
  int drop = 0;
  n.cwiseAbs().maxCoeff(&drop);
  const int i = (drop + 1) % 3, j = (drop + 2) % 3;
  auto to2 = [&](const Vector3& v) { return P2{v[i], v[j]}; };
  const P2 p2 = to2(p), q2 = to2(q), t0 = to2(t[0]), t1 = to2(t[1]), t2 = to2(t[2]);
  const double o0 = Orient2(t0, t1, p2), o1 = Orient2(t1, t2, p2), o2 = Orient2(t2, t0, p2);
  if ((o0 >= 0 && o1 >= 0 && o2 >= 0) || (o0 <= 0 && o1 <= 0 && o2 <= 0)) return true;
  return SegmentsIntersect2(p2, q2, t0, t1) || SegmentsIntersect2(p2, q2, t1, t2) ||
         SegmentsIntersect2(p2, q2, t2, t0);
}

// Segment p-q against non-degenerate triangle t (normal n), given the
// orientations op, oq of p and q against t's plane.
bool SegmentHitsTriangle(const Vector3& p, const Vector3& q, double op, double oq,
                         const Vector3* t, const Vector3& n) {
  if ((op > 0 && oq > 0) || (op < 0 && oq < 0)) return false;
  if (op == 0 && oq == 0) return CoplanarSegmentHitsTriangle(p, q, t, n);
  // The line p-q passes through the triangle iff it turns the same way
  // around all three edges.
  const double s0 = Orient3(p, q, t[0], t[1]);
  const double s1 = Orient3(p, q, t[1], t[2]);
  const double s2 = Orient3(p, q, t[2], t[0]);
  return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

inline bool Degenerate(const Vector3* t, const Vector3& n) {
  const double scale = (t[1] - t[0]).squaredNorm() + (t[2] - t[0]).squaredNorm();
  return !(n.norm() > 1e-14 * scale);
}

// Orientations of the points p against the plane of t; false if all three
// are strictly on one side.
bool Straddles(const Vector3* t, const Vector3* p, double o[3]) {
  int pos = 0, neg = 0;
  for (int i = 0; i < 3; ++i) {
    o[i] = Orient3(t[0], t[1], t[2], p[i]);
    pos += o[i] > 0;
    neg += o[i] < 0;
  }
  return pos < 3 && neg < 3;
}

// Non-coplanar triangles meet iff an edge of one meets the other (the ends of
// their common segment lie on edges); coplanar ones iff an edge of one meets
// the other's region, which the in-plane segment test covers.
bool TrianglesIntersect(const Vector3* a, const Vector3* b) {
  const Vector3 na = (a[1] - a[0]).cross(a[2] - a[0]);
  const Vector3 nb = (b[1] - b[0]).cross(b[2] - b[0]);
  const bool deg_a = Degenerate(a, na), deg_b = Degenerate(b, nb);
  if (deg_a && deg_b) return false;
  double oa[3], ob[3];  // a's vertices against b's plane, and back
  if (!deg_b && !Straddles(b, a, oa)) return false;
  if (!deg_a && !Straddles(a, b, ob)) return false;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    if (!deg_b && SegmentHitsTriangle(a[i], a[i1], oa[i], oa[i1], b, nb)) return true;
    if (!deg_a && SegmentHitsTriangle(b[i], b[i1], ob[i], ob[i1], a, na)) return true;
  }
  return false;
}

struct Box3 {
  double x0, x1, y0, y1, z0, z1;
  int tri;
};

void TriangleBoxes(const PlacedMesh& m, double eps, std::vector<Box3>* boxes) {
  boxes->clear();
  for (int t = 0; t < m.num_triangles(); ++t) {
    const auto& tri = (*m.triangles)[t];
    const Vector3 lo = m.p_OV[tri[0]].cwiseMin(m.p_OV[tri[1]]).cwiseMin(m.p_OV[tri[2]]);
    const Vector3 hi = m.p_OV[tri[0]].cwiseMax(m.p_OV[tri[1]]).cwiseMax(m.p_OV[tri[2]]);
    boxes->push_back({lo.x() - eps, hi.x() + eps, lo.y() - eps, hi.y() + eps, lo.z() - eps,
                      hi.z() + eps, t});
  }
  std::sort(boxes->begin(), boxes->end(),
            [](const Box3& l, const Box3& r) { return l.x0 < r.x0; });
}

}  // namespace

bool SurfacesIntersect(const PairGeometry& g) {
  std::vector<Box3> boxes_P, boxes_S;
  TriangleBoxes(g.P, g.eps_len, &boxes_P);
  TriangleBoxes(g.S, g.eps_len, &boxes_S);
  std::vector<int> active_P, active_S;
  bool hit = false;
  SweepPairs(boxes_P, boxes_S, &active_P, &active_S, [&](const Box3& bp, const Box3& bs) {
    if (bs.y0 > bp.y1 || bp.y0 > bs.y1 || bs.z0 > bp.z1 || bp.z0 > bs.z1) return false;
    const auto& tp = (*g.P.triangles)[bp.tri];
    const auto& ts = (*g.S.triangles)[bs.tri];
    const Vector3 a[3] = {g.P.p_OV[tp[0]], g.P.p_OV[tp[1]], g.P.p_OV[tp[2]]};
    const Vector3 b[3] = {g.S.p_OV[ts[0]], g.S.p_OV[ts[1]], g.S.p_OV[ts[2]]};
    hit = TrianglesIntersect(a, b);
    return hit;
  });
  return hit;
}

}  // namespace reference
}  // namespace pd
