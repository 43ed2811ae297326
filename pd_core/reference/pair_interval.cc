#include "pd_core/reference/pair_interval.h"

#include <algorithm>
#include <cmath>

namespace pd {
namespace reference {
namespace {

// (x, y, h) normalised and oriented along +u; zero (undefined) if it is zero.
Normal MakeNormal(double x, double y, double h) {
  const double norm = std::sqrt(x * x + y * y + h * h);
  if (!(norm > 0.0)) return {};
  const double scale = (h < 0.0 ? -1.0 : 1.0) / norm;
  return {x * scale, y * scale, h * scale};
}

inline double Cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }
inline double L1(double x, double y) { return std::abs(x) + std::abs(y); }

// Events of point X lying on segment s0-s1 (within eps): sign * (h_X - h_seg).
// A segment parallel to u (projected to a point) contributes both its heights.
inline void PointOnSegment(const Proj& X, const Proj& s0, const Proj& s1, double eps,
                           double sign, Interval* iv) {
  const double dx = s1.x - s0.x, dy = s1.y - s0.y;
  const double rx = X.x - s0.x, ry = X.y - s0.y;
  const double n = L1(dx, dy);
  if (n <= eps) {
    if (L1(rx, ry) <= 2.0 * eps) {
      iv->Add(sign * (X.h - s0.h), Normal{}, eps);
      iv->Add(sign * (X.h - s1.h), Normal{}, eps);
    }
    return;
  }
  if (std::abs(Cross2(dx, dy, rx, ry)) > eps * n) return;
  double t = (rx * dx + ry * dy) / (dx * dx + dy * dy);
  const double tt = 2.0 * eps / n;
  if (t < -tt || t > 1.0 + tt) return;
  t = std::clamp(t, 0.0, 1.0);
  iv->Add(sign * (X.h - (s0.h + t * (s1.h - s0.h))), Normal{}, eps);
}

// side[k][j] = cross(edge k of t, vertex j of o - start of edge k): the
// signed distance of o's vertex j from t's edge line k times the edge length.
void Sides(const TriProj& t, const TriProj& o, double side[3][3]) {
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 3; ++j) {
      side[k][j] = Cross2(t.ex[k], t.ey[k], o.v[j].x - t.v[k].x, o.v[j].y - t.v[k].y);
    }
  }
}

// Is o more than eps outside an edge line of t (only the outer side counts
// unless t is flat)? Point-like edges of a flat t have no line.
bool Separates(const TriProj& t, const double side[3][3], double eps) {
  for (int k = 0; k < 3; ++k) {
    if (t.len1[k] <= eps) continue;
    const double tol = eps * t.len1[k];
    const double s0 = side[k][0], s1 = side[k][1], s2 = side[k][2];
    if (!t.flat) {
      if (t.orient * s0 < -tol && t.orient * s1 < -tol && t.orient * s2 < -tol) return true;
    } else if ((s0 < -tol && s1 < -tol && s2 < -tol) || (s0 > tol && s1 > tol && s2 > tol)) {
      return true;
    }
  }
  return false;
}

// Height of non-flat t over o's vertex j, if that vertex lies in t within
// eps. The weights are clamped so the height is that of a point of t.
bool HeightOver(const TriProj& t, const double side[3][3], int j, double eps, double* h) {
  double w[3];
  for (int k = 0; k < 3; ++k) {
    w[k] = t.orient * side[k][j];  // weight of the vertex opposite edge k
    if (w[k] < -eps * t.len1[k]) return false;
    w[k] = std::max(w[k], 0.0);
  }
  const double sum = w[0] + w[1] + w[2];
  if (!(sum > 0.0)) return false;
  *h = (w[0] * t.v[2].h + w[1] * t.v[0].h + w[2] * t.v[1].h) / sum;
  return true;
}

}  // namespace

TriProj MakeTriProj(const Proj& p0, const Proj& p1, const Proj& p2, double eps) {
  TriProj t;
  t.v[0] = p0;
  t.v[1] = p1;
  t.v[2] = p2;
  for (int k = 0; k < 3; ++k) {
    const Proj& a = t.v[k];
    const Proj& b = t.v[(k + 1) % 3];
    t.ex[k] = b.x - a.x;
    t.ey[k] = b.y - a.y;
    t.eh[k] = b.h - a.h;
    t.len1[k] = L1(t.ex[k], t.ey[k]);
  }
  const double area2 = Cross2(t.ex[0], t.ey[0], -t.ex[2], -t.ey[2]);
  t.flat = std::abs(area2) <= eps * (t.len1[0] + t.len1[1] + t.len1[2]);
  t.orient = area2 >= 0.0 ? 1.0 : -1.0;
  if (!t.flat) {
    const double nx = t.ey[0] * -t.eh[2] - t.eh[0] * -t.ey[2];
    const double ny = t.eh[0] * -t.ex[2] - t.ex[0] * -t.eh[2];
    t.n = MakeNormal(nx, ny, area2);
  }
  return t;
}

Interval PairInterval(const TriProj& a, const TriProj& b, double eps) {
  Interval iv;
  double side_b[3][3], side_a[3][3];  // b's vertices against a's edges, and back
  Sides(a, b, side_b);
  if (Separates(a, side_b, eps)) return iv;
  Sides(b, a, side_a);
  if (Separates(b, side_a, eps)) return iv;

  double h;
  for (int j = 0; j < 3; ++j) {  // vertices of b over a
    if (!a.flat) {
      if (HeightOver(a, side_b, j, eps, &h)) iv.Add(b.v[j].h - h, a.n, eps);
    } else {
      for (int k = 0; k < 3; ++k) PointOnSegment(b.v[j], a.v[k], a.v[(k + 1) % 3], eps, 1.0, &iv);
    }
  }
  for (int k = 0; k < 3; ++k) {  // vertices of a over b
    if (!b.flat) {
      if (HeightOver(b, side_a, k, eps, &h)) iv.Add(h - a.v[k].h, b.n, eps);
    } else {
      for (int j = 0; j < 3; ++j) PointOnSegment(a.v[k], b.v[j], b.v[(j + 1) % 3], eps, -1.0, &iv);
    }
  }

  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      // Edge a_k crosses edge b_j where the side functions of each edge line,
      // linear along the other edge, vanish: alpha = fa0 / (fa0 - fa1) along
      // a_k and beta = fb0 / (fb0 - fb1) along b_j.
      const double fa0 = side_a[j][k], fa1 = side_a[j][k1];
      const double fb0 = side_b[k][j], fb1 = side_b[k][j1];
      const double da = fa0 - fa1, db = fb0 - fb1;
      const double n1 = a.len1[k], n2 = b.len1[j];
      if (n1 > eps && n2 > eps) {
        // Quick reject: one edge lies more than eps to one side of the other's line.
        const double tol_a = eps * n1, tol_b = eps * n2;
        if ((fb0 > tol_a && fb1 > tol_a) || (fb0 < -tol_a && fb1 < -tol_a)) continue;
        if ((fa0 > tol_b && fa1 > tol_b) || (fa0 < -tol_b && fa1 < -tol_b)) continue;
      }
      const double parallel_tol = 1e-12 * n1 * n2;
      if (n1 > eps && n2 > eps && std::abs(da) > parallel_tol && std::abs(db) > parallel_tol) {
        // Tolerances of 2 eps along each edge, scaled by the denominators
        // so that most pairs are rejected without a division.
        const double alpha_s = da > 0.0 ? fa0 : -fa0, abs_da = std::abs(da);
        const double beta_s = db > 0.0 ? fb0 : -fb0, abs_db = std::abs(db);
        const double ta = 2.0 * eps / n1 * abs_da, tb = 2.0 * eps / n2 * abs_db;
        if (alpha_s < -ta || alpha_s > abs_da + ta || beta_s < -tb || beta_s > abs_db + tb) {
          continue;
        }
        const double alpha = std::clamp(alpha_s / abs_da, 0.0, 1.0);
        const double beta = std::clamp(beta_s / abs_db, 0.0, 1.0);
        // The contact normal is a_k x b_j.
        const double nx = a.ey[k] * b.eh[j] - a.eh[k] * b.ey[j];
        const double ny = a.eh[k] * b.ex[j] - a.ex[k] * b.eh[j];
        const double nh = a.ex[k] * b.ey[j] - a.ey[k] * b.ex[j];
        iv.Add((b.v[j].h + beta * b.eh[j]) - (a.v[k].h + alpha * a.eh[k]),
               MakeNormal(nx, ny, nh), eps);
      } else {
        // Parallel (or point-like) projections: the overlap ends at endpoints.
        PointOnSegment(b.v[j], a.v[k], a.v[k1], eps, 1.0, &iv);
        PointOnSegment(b.v[j1], a.v[k], a.v[k1], eps, 1.0, &iv);
        PointOnSegment(a.v[k], b.v[j], b.v[j1], eps, -1.0, &iv);
        PointOnSegment(a.v[k1], b.v[j], b.v[j1], eps, -1.0, &iv);
      }
    }
  }
  return iv;
}

}  // namespace reference
}  // namespace pd
