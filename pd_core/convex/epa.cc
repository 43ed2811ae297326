#include "pd_core/convex/epa.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pd {

namespace {

using Face = EpaScratch::Face;
constexpr size_t kMaxFaces = 4096;

// A unit vector perpendicular to d (non-zero).
Vector3 AnyPerpendicular(const Vector3& d) {
  const Vector3 a = std::abs(d.x()) < 0.6 ? Vector3::UnitX() : Vector3::UnitY();
  return d.cross(a).normalized();
}

struct Builder {
  const MinkowskiDifference& D;
  EpaScratch* s;
  EpaResult* result;

  // Records support value along a unit n as a candidate answer.
  Vector3 SupportAlong(const Vector3& n) {
    const Vector3 w = D.Support(n);
    const double h = n.dot(w);
    if (h < result->depth) result->depth = h, result->normal_W = n;
    return w;
  }

  void AddFace(int a, int b, int c) {
    Face f{{a, b, c}, {-1, -1, -1}, {-1, -1, -1}, Vector3::Zero(),
           std::numeric_limits<double>::infinity(), true};
    const Vector3& pa = s->vertices[a];
    Vector3 n = (s->vertices[b] - pa).cross(s->vertices[c] - pa);
    const double len = n.norm();
    if (len > 0.0) {
      n /= len;
      f.n = n;
      f.d = n.dot(pa);
    }
    s->faces.push_back(f);
  }

  // Adds a face with orientation chosen so that `interior` is behind it.
  void AddOrientedFace(int a, int b, int c, const Vector3& interior) {
    const Vector3& pa = s->vertices[a];
    const Vector3 n = (s->vertices[b] - pa).cross(s->vertices[c] - pa);
    if (n.dot(interior - pa) > 0.0) std::swap(b, c);
    AddFace(a, b, c);
  }
};

// Links the open edges of faces [first, end) to each other and to older
// faces by matching reversed vertex pairs.
void LinkFaces(EpaScratch* s, int first) {
  const int n = static_cast<int>(s->faces.size());
  for (int f = first; f < n; ++f)
    for (int k = 0; k < 3; ++k) {
      Face& F = s->faces[f];
      if (F.adj[k] >= 0) continue;
      const int a = F.v[k], b = F.v[(k + 1) % 3];
      for (int g = first; g < n && F.adj[k] < 0; ++g) {
        if (g == f) continue;
        Face& G = s->faces[g];
        for (int j = 0; j < 3; ++j)
          if (G.v[j] == b && G.v[(j + 1) % 3] == a) {
            F.adj[k] = g, F.adj_edge[k] = j;
            G.adj[j] = f, G.adj_edge[j] = k;
            break;
          }
      }
    }
}

}  // namespace

EpaResult Epa(const MinkowskiDifference& D, const GjkSimplex& simplex, double tol_abs,
              int max_iterations, EpaScratch* scratch) {
  EpaResult result;
  result.depth = std::numeric_limits<double>::infinity();
  EpaScratch& s = *scratch;
  s.vertices.clear();
  s.faces.clear();
  Builder B{D, &s, &result};
  for (int i = 0; i < simplex.size; ++i) s.vertices.push_back(simplex.points[i]);

  // Blow a degenerate simplex up to a triangle.
  if (s.vertices.size() == 1) {
    for (int k = 0; k < 6 && s.vertices.size() == 1; ++k) {
      const Vector3 dir = (k % 2 ? -1.0 : 1.0) * Vector3::Unit(k / 2);
      const Vector3 w = B.SupportAlong(dir);
      if ((w - s.vertices[0]).norm() > tol_abs) s.vertices.push_back(w);
    }
    if (s.vertices.size() == 1) {  // the set is a point: depth 0
      result.depth = 0.0;
      result.converged = true;
      return result;
    }
  }
  if (s.vertices.size() == 2) {
    const Vector3 axis = (s.vertices[1] - s.vertices[0]).normalized();
    const Vector3 e1 = AnyPerpendicular(axis), e2 = axis.cross(e1);
    for (int k = 0; k < 6 && s.vertices.size() == 2; ++k) {
      const double a = M_PI / 3.0 * k;
      const Vector3 dir = std::cos(a) * e1 + std::sin(a) * e2;
      const Vector3 w = B.SupportAlong(dir);
      const Vector3 off = (w - s.vertices[0]) - (w - s.vertices[0]).dot(axis) * axis;
      if (off.norm() > tol_abs) s.vertices.push_back(w);
    }
    if (s.vertices.size() == 2) {  // the set is a segment: depth 0
      result.depth = 0.0;
      result.converged = true;
      return result;
    }
  }
  if (s.vertices.size() == 3) {
    const Vector3 a = s.vertices[0];
    Vector3 n = (s.vertices[1] - a).cross(s.vertices[2] - a);
    if (n.norm() <= 0.0) n = AnyPerpendicular(s.vertices[1] - a);
    n.normalize();
    const Vector3 up = B.SupportAlong(n), down = B.SupportAlong(-n);
    const bool has_up = n.dot(up - a) > tol_abs, has_down = -n.dot(down - a) > tol_abs;
    if (!has_up || !has_down) {  // flat on one side: the origin is on the boundary
      result.depth = 0.0;
      result.normal_W = has_up ? -n : n;
      result.converged = true;
      return result;
    }
    // A tetrahedron (always convex, so orientation by an interior point is
    // consistent) with the origin on or inside it: the taller apex.
    s.vertices.push_back(n.dot(up - a) >= -n.dot(down - a) ? up : down);
  }
  if (s.vertices.size() == 4) {
    const Vector3 interior =
        0.25 * (s.vertices[0] + s.vertices[1] + s.vertices[2] + s.vertices[3]);
    B.AddOrientedFace(0, 1, 2, interior);
    B.AddOrientedFace(0, 3, 1, interior);
    B.AddOrientedFace(0, 2, 3, interior);
    B.AddOrientedFace(1, 3, 2, interior);
    LinkFaces(&s, 0);
  }

  for (result.iterations = 1; result.iterations <= max_iterations; ++result.iterations) {
    int best = -1;
    for (int f = 0; f < static_cast<int>(s.faces.size()); ++f)
      if (s.faces[f].alive && s.faces[f].n.squaredNorm() > 0.0 &&
          (best < 0 || s.faces[f].d < s.faces[best].d))
        best = f;
    if (best < 0) break;
    const Face nearest = s.faces[best];
    result.lower_bound = std::max(0.0, nearest.d);
    const Vector3 w = B.SupportAlong(nearest.n);
    if (result.depth - result.lower_bound <= tol_abs) {
      result.converged = true;
      break;
    }
    // Unreachable unless round-off: the face's own bound closes the gap.
    if (!(nearest.n.dot(w) - nearest.d > tol_abs)) break;
    // Remove the faces that see w, connected to the nearest one; the
    // horizon is the edges from a removed face to a kept one.
    const int iw = static_cast<int>(s.vertices.size());
    s.vertices.push_back(w);
    s.horizon.clear();
    s.stack.clear();
    s.faces[best].alive = false;
    for (int k = 2; k >= 0; --k) s.stack.emplace_back(s.faces[best].adj[k], s.faces[best].adj_edge[k]);
    bool broken = false;
    while (!s.stack.empty()) {
      const auto [f, e] = s.stack.back();
      s.stack.pop_back();
      if (f < 0) {
        broken = true;
        break;
      }
      Face& F = s.faces[f];
      if (!F.alive) continue;
      const bool visible =
          F.n.squaredNorm() > 0.0 ? F.n.dot(w - s.vertices[F.v[0]]) > 0.0 : true;
      if (!visible) {
        s.horizon.emplace_back(f, e);
        continue;
      }
      F.alive = false;
      s.stack.emplace_back(F.adj[(e + 2) % 3], F.adj_edge[(e + 2) % 3]);
      s.stack.emplace_back(F.adj[(e + 1) % 3], F.adj_edge[(e + 1) % 3]);
    }
    if (broken || s.horizon.size() < 3 || s.faces.size() + s.horizon.size() > kMaxFaces) break;
    const int first = static_cast<int>(s.faces.size());
    for (const auto& [f, e] : s.horizon) {
      // Kept face f's edge e runs a -> b; the new face runs b -> a -> w.
      const int a = s.faces[f].v[e], b = s.faces[f].v[(e + 1) % 3];
      B.AddFace(b, a, iw);
      Face& N = s.faces.back();
      const int nf = static_cast<int>(s.faces.size()) - 1;
      N.adj[0] = f, N.adj_edge[0] = e;
      s.faces[f].adj[e] = nf, s.faces[f].adj_edge[e] = 0;
    }
    LinkFaces(&s, first);
  }
  if (!std::isfinite(result.depth)) result.depth = 0.0;
  return result;
}

}  // namespace pd
