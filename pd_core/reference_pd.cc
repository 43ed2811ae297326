#include "pd_core/reference_pd.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <utility>

namespace pd {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Feature tests accept points this far (relative to the pair's extent) outside
// a triangle or segment, so that rounding never drops a touching event.
constexpr double kRelativeLengthTol = 1e-12;

// ---------------------------------------------------------------------------
// Meshes placed in world and re-centred on a common origin O, so tolerances
// scale with the pair and not with its distance from the world origin.

struct PlacedMesh {
  std::vector<Vector3> p_OV;  // vertex positions relative to O, world axes (m)
  const std::vector<Eigen::Vector3i>* triangles = nullptr;
  std::vector<int> component_vertices;  // one vertex of each connected component
  bool closed = false;
  int num_triangles() const { return static_cast<int>(triangles->size()); }
};

struct PairGeometry {
  PlacedMesh P, S;
  double eps_len = 0.0;  // absolute length tolerance of feature tests (m)
  double size = 0.0;     // sum of bounding-sphere radii (m)
};

// Without the surfaces touching, each connected piece of a mesh lies wholly
// inside or outside the other mesh, so one vertex per piece decides containment.
std::vector<int> ComponentVertices(const TriangleMesh& mesh) {
  std::vector<int> parent(mesh.vertices.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) used[t[k]] = 1;
    const int r0 = find(t[0]);
    parent[find(t[1])] = r0;
    parent[find(t[2])] = r0;
  }
  std::vector<int> reps;
  for (int v = 0; v < static_cast<int>(parent.size()); ++v) {
    if (used[v] && find(v) == v) reps.push_back(v);
  }
  return reps;
}

double BoundingRadius(const TriangleMesh& mesh) {
  const MeshBounds b = ComputeBounds(mesh);
  const Vector3 c = b.center();
  double r2 = 0.0;
  for (const Vector3& v : mesh.vertices) r2 = std::max(r2, (v - c).squaredNorm());
  return std::sqrt(r2);
}

PlacedMesh Place(const TriangleMesh& mesh, const Isometry3& X_WM, const Vector3& p_WO,
                 bool closed) {
  PlacedMesh m;
  m.p_OV.reserve(mesh.vertices.size());
  for (const Vector3& p_MV : mesh.vertices) m.p_OV.push_back(X_WM * p_MV - p_WO);
  m.triangles = &mesh.triangles;
  m.component_vertices = ComponentVertices(mesh);
  m.closed = closed;
  return m;
}

PairGeometry MakePair(const TriangleMesh& probe, const Isometry3& X_WP, bool probe_closed,
                      const TriangleMesh& scene, const Isometry3& X_WS, bool scene_closed) {
  Vector3 lo = Vector3::Constant(kInf), hi = Vector3::Constant(-kInf);
  for (const Vector3& v : probe.vertices) {
    lo = lo.cwiseMin(X_WP * v);
    hi = hi.cwiseMax(X_WP * v);
  }
  for (const Vector3& v : scene.vertices) {
    lo = lo.cwiseMin(X_WS * v);
    hi = hi.cwiseMax(X_WS * v);
  }
  const Vector3 p_WO = (probe.vertices.empty() && scene.vertices.empty())
                           ? Vector3::Zero()
                           : Vector3(0.5 * (lo + hi));
  PairGeometry g;
  g.P = Place(probe, X_WP, p_WO, probe_closed);
  g.S = Place(scene, X_WS, p_WO, scene_closed);
  double extent = 0.0;
  for (const auto* m : {&g.P, &g.S}) {
    for (const Vector3& p : m->p_OV) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  }
  g.eps_len = kRelativeLengthTol * std::max(extent, std::numeric_limits<double>::min());
  g.size = BoundingRadius(probe) + BoundingRadius(scene);
  return g;
}

// ---------------------------------------------------------------------------
// Point in closed mesh by ray parity.

// Parity of the crossings of the ray x + t d (t > 0) with the mesh. *clean is
// cleared when the ray passes near an edge or vertex, runs parallel to a
// triangle it may graze, or x is on the surface: then the count is unreliable.
bool RayParityOdd(const Vector3& x, const Vector3& d, const PlacedMesh& m, double eps_len,
                  bool* clean) {
  constexpr double kBaryTol = 1e-9;
  bool odd = false;
  *clean = true;
  for (const auto& t : *m.triangles) {
    const Vector3& v0 = m.p_OV[t[0]];
    const Vector3 e1 = m.p_OV[t[1]] - v0;
    const Vector3 e2 = m.p_OV[t[2]] - v0;
    const Vector3 pvec = d.cross(e2);
    const double det = e1.dot(pvec);
    const Vector3 tvec = x - v0;
    if (std::abs(det) <= 1e-14 * e1.norm() * e2.norm()) {
      // Parallel to the plane: it can only graze the triangle, and only if x
      // is in that plane.
      const Vector3 n = e1.cross(e2);
      const double n_norm = n.norm();
      if (n_norm > 0.0 && std::abs(n.dot(tvec)) <= eps_len * n_norm) *clean = false;
      continue;
    }
    const double inv = 1.0 / det;
    const double b1 = tvec.dot(pvec) * inv;
    if (b1 < -kBaryTol || b1 > 1.0 + kBaryTol) continue;
    const Vector3 qvec = tvec.cross(e1);
    const double b2 = d.dot(qvec) * inv;
    if (b2 < -kBaryTol || b1 + b2 > 1.0 + kBaryTol) continue;
    const double s = e2.dot(qvec) * inv;
    if (s < -eps_len) continue;
    if (b1 < kBaryTol || b2 < kBaryTol || b1 + b2 > 1.0 - kBaryTol || s <= eps_len) {
      *clean = false;
      continue;
    }
    odd = !odd;
  }
  return odd;
}

// Majority of three clean rays in fixed pseudo-random directions.
bool PointInside(const Vector3& x, const PlacedMesh& m, double eps_len) {
  std::mt19937 rng(20240611u);
  std::normal_distribution<double> gauss;
  int votes_in = 0, votes_out = 0, dirty_in = 0, dirty_out = 0;
  for (int attempt = 0; attempt < 24 && votes_in + votes_out < 3; ++attempt) {
    Vector3 d(gauss(rng), gauss(rng), gauss(rng));
    d.normalize();
    bool clean = true;
    const bool odd = RayParityOdd(x, d, m, eps_len, &clean);
    if (clean) {
      (odd ? votes_in : votes_out)++;
    } else {
      (odd ? dirty_in : dirty_out)++;
    }
  }
  if (votes_in + votes_out == 0) return dirty_in > dirty_out;
  return votes_in > votes_out;
}

// With P moved by t_W: is a piece of P inside closed S, or of S inside closed P?
// Only meaningful where the two surfaces do not touch.
bool Contained(const PairGeometry& g, const Vector3& t_W) {
  if (g.S.closed) {
    for (int v : g.P.component_vertices) {
      if (PointInside(g.P.p_OV[v] + t_W, g.S, g.eps_len)) return true;
    }
  }
  if (g.P.closed) {
    for (int v : g.S.component_vertices) {
      if (PointInside(g.S.p_OV[v] - t_W, g.P, g.eps_len)) return true;
    }
  }
  return false;
}

// ---------------------------------------------------------------------------
// Sort-and-sweep over boxes sorted by x0: calls on_pair(a, b) for every pair
// whose x ranges overlap; on_pair tests the other axes and returns true to stop.

template <typename Box, typename OnPair>
void SweepPairs(const std::vector<Box>& a, const std::vector<Box>& b, std::vector<int>* active_a,
                std::vector<int>* active_b, OnPair&& on_pair) {
  active_a->clear();
  active_b->clear();
  size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    const bool take_a = j >= b.size() || (i < a.size() && a[i].x0 <= b[j].x0);
    const Box& box = take_a ? a[i] : b[j];
    std::vector<int>& others = take_a ? *active_b : *active_a;
    const std::vector<Box>& other_boxes = take_a ? b : a;
    for (size_t k = 0; k < others.size();) {
      const Box& o = other_boxes[others[k]];
      if (o.x1 < box.x0) {  // ended before this one starts: never overlaps again
        others[k] = others.back();
        others.pop_back();
        continue;
      }
      if (take_a ? on_pair(box, o) : on_pair(o, box)) return;
      ++k;
    }
    if (take_a) {
      active_a->push_back(static_cast<int>(i++));
    } else {
      active_b->push_back(static_cast<int>(j++));
    }
  }
}

// ---------------------------------------------------------------------------
// Directional exit. Coordinates (x, y) in the plane normal to u, h along u.
// Triangle a of P moved by s*u touches triangle b of S exactly when their
// projections share a point q and s = h_b(q) - h_a(q); the set of such s is
// one closed interval whose ends are feature events: a vertex of one over the
// other triangle, or edge-edge crossings (endpoints on collinear edges, both
// heights of an edge parallel to u, when the projection degenerates).

struct Proj {
  double x, y, h;
};

struct Box2 {
  double x0, x1, y0, y1;  // projected bounds, inflated by eps_len
  double h0, h1;          // range along u
  int tri;
};

struct Interval {
  double lo = kInf, hi = -kInf;
  void Add(double s) {
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
};

inline double Cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }
inline double L1(double x, double y) { return std::abs(x) + std::abs(y); }

// Height over X of the non-degenerate projected triangle t (signed doubled
// area area2), if X lies in it within eps; barycentric weights are clamped
// so the height is that of a point of the triangle.
inline bool HeightOver(const Proj& X, const Proj& t0, const Proj& t1, const Proj& t2,
                       double area2, double eps, double* h) {
  const double sgn = area2 > 0.0 ? 1.0 : -1.0;
  const double e0x = t1.x - t0.x, e0y = t1.y - t0.y;
  double w2 = sgn * Cross2(e0x, e0y, X.x - t0.x, X.y - t0.y);
  if (w2 < -eps * L1(e0x, e0y)) return false;
  const double e1x = t2.x - t1.x, e1y = t2.y - t1.y;
  double w0 = sgn * Cross2(e1x, e1y, X.x - t1.x, X.y - t1.y);
  if (w0 < -eps * L1(e1x, e1y)) return false;
  const double e2x = t0.x - t2.x, e2y = t0.y - t2.y;
  double w1 = sgn * Cross2(e2x, e2y, X.x - t2.x, X.y - t2.y);
  if (w1 < -eps * L1(e2x, e2y)) return false;
  w0 = std::max(w0, 0.0);
  w1 = std::max(w1, 0.0);
  w2 = std::max(w2, 0.0);
  const double sum = w0 + w1 + w2;
  if (!(sum > 0.0)) return false;
  *h = (w0 * t0.h + w1 * t1.h + w2 * t2.h) / sum;
  return true;
}

// Events of point X lying on segment s0-s1 (within eps): sign * (h_X - h_seg).
// A segment parallel to u (projected to a point) contributes both its heights.
inline void PointOnSegment(const Proj& X, const Proj& s0, const Proj& s1, double eps,
                           double sign, Interval* iv) {
  const double dx = s1.x - s0.x, dy = s1.y - s0.y;
  const double rx = X.x - s0.x, ry = X.y - s0.y;
  const double n = L1(dx, dy);
  if (n <= eps) {
    if (L1(rx, ry) <= 2.0 * eps) {
      iv->Add(sign * (X.h - s0.h));
      iv->Add(sign * (X.h - s1.h));
    }
    return;
  }
  if (std::abs(Cross2(dx, dy, rx, ry)) > eps * n) return;
  double t = (rx * dx + ry * dy) / (dx * dx + dy * dy);
  const double tt = 2.0 * eps / n;
  if (t < -tt || t > 1.0 + tt) return;
  t = std::clamp(t, 0.0, 1.0);
  iv->Add(sign * (X.h - (s0.h + t * (s1.h - s0.h))));
}

// Events of edge p0-p1 of A against edge q0-q1 of B: s = h_q - h_p.
inline void EdgeEdge(const Proj& p0, const Proj& p1, const Proj& q0, const Proj& q1,
                     double eps, Interval* iv) {
  const double d1x = p1.x - p0.x, d1y = p1.y - p0.y;
  const double d2x = q1.x - q0.x, d2y = q1.y - q0.y;
  const double n1 = L1(d1x, d1y), n2 = L1(d2x, d2y);
  const double denom = Cross2(d1x, d1y, d2x, d2y);
  if (n1 > eps && n2 > eps && std::abs(denom) > 1e-12 * n1 * n2) {
    const double rx = q0.x - p0.x, ry = q0.y - p0.y;
    double alpha = Cross2(rx, ry, d2x, d2y) / denom;
    double beta = Cross2(rx, ry, d1x, d1y) / denom;
    const double ta = 2.0 * eps / n1, tb = 2.0 * eps / n2;
    if (alpha < -ta || alpha > 1.0 + ta || beta < -tb || beta > 1.0 + tb) return;
    alpha = std::clamp(alpha, 0.0, 1.0);
    beta = std::clamp(beta, 0.0, 1.0);
    iv->Add((q0.h + beta * (q1.h - q0.h)) - (p0.h + alpha * (p1.h - p0.h)));
    return;
  }
  // Parallel (or point-like) projections: the overlap ends at endpoints.
  PointOnSegment(q0, p0, p1, eps, 1.0, iv);
  PointOnSegment(q1, p0, p1, eps, 1.0, iv);
  PointOnSegment(p0, q0, q1, eps, -1.0, iv);
  PointOnSegment(p1, q0, q1, eps, -1.0, iv);
}

inline double Area2(const Proj* t) {
  return Cross2(t[1].x - t[0].x, t[1].y - t[0].y, t[2].x - t[0].x, t[2].y - t[0].y);
}
inline double PerimeterL1(const Proj* t) {
  return L1(t[1].x - t[0].x, t[1].y - t[0].y) + L1(t[2].x - t[1].x, t[2].y - t[1].y) +
         L1(t[0].x - t[2].x, t[0].y - t[2].y);
}

// The closed set of s with (a + s u) intersecting b; empty if lo > hi.
Interval PairInterval(const Proj* a, const Proj* b, double eps) {
  Interval iv;
  const double area_a = Area2(a), area_b = Area2(b);
  // A projected triangle thinner than eps is parallel to u: its own face events
  // are replaced by events on its edges.
  const bool flat_a = std::abs(area_a) <= eps * PerimeterL1(a);
  const bool flat_b = std::abs(area_b) <= eps * PerimeterL1(b);
  double h;
  for (int i = 0; i < 3; ++i) {
    if (!flat_b) {
      if (HeightOver(a[i], b[0], b[1], b[2], area_b, eps, &h)) iv.Add(h - a[i].h);
    } else {
      for (int k = 0; k < 3; ++k) PointOnSegment(a[i], b[k], b[(k + 1) % 3], eps, -1.0, &iv);
    }
  }
  for (int j = 0; j < 3; ++j) {
    if (!flat_a) {
      if (HeightOver(b[j], a[0], a[1], a[2], area_a, eps, &h)) iv.Add(b[j].h - h);
    } else {
      for (int k = 0; k < 3; ++k) PointOnSegment(b[j], a[k], a[(k + 1) % 3], eps, 1.0, &iv);
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      EdgeEdge(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3], eps, &iv);
    }
  }
  return iv;
}

// Per-direction buffers, reused across directions of one query.
struct DirectionalScratch {
  std::vector<Proj> proj_P, proj_S;
  std::vector<Box2> boxes_P, boxes_S;
  std::vector<int> active_P, active_S;
  std::vector<std::pair<double, double>> intervals;
};

void Project(const PlacedMesh& m, const Vector3& e1, const Vector3& e2, const Vector3& u,
             double eps, std::vector<Proj>* proj, std::vector<Box2>* boxes) {
  proj->resize(m.p_OV.size());
  for (size_t v = 0; v < m.p_OV.size(); ++v) {
    const Vector3& p = m.p_OV[v];
    (*proj)[v] = {p.dot(e1), p.dot(e2), p.dot(u)};
  }
  boxes->resize(m.triangles->size());
  for (int t = 0; t < m.num_triangles(); ++t) {
    const auto& tri = (*m.triangles)[t];
    const Proj& a = (*proj)[tri[0]];
    const Proj& b = (*proj)[tri[1]];
    const Proj& c = (*proj)[tri[2]];
    (*boxes)[t] = {std::min({a.x, b.x, c.x}) - eps, std::max({a.x, b.x, c.x}) + eps,
                   std::min({a.y, b.y, c.y}) - eps, std::max({a.y, b.y, c.y}) + eps,
                   std::min({a.h, b.h, c.h}),       std::max({a.h, b.h, c.h}),
                   t};
  }
  std::sort(boxes->begin(), boxes->end(),
            [](const Box2& l, const Box2& r) { return l.x0 < r.x0; });
}

// Unit vectors e1, e2 completing u to a right-handed frame; exact for axes.
void Complete(const Vector3& u, Vector3* e1, Vector3* e2) {
  const Vector3 a = std::abs(u.x()) < 0.9 ? Vector3::UnitX() : Vector3::UnitY();
  *e1 = a.cross(u).normalized();
  *e2 = u.cross(*e1);
}

struct Exit {
  bool colliding = false;  // at s = 0
  double distance = 0.0;   // first free s >= 0 (m), 0 if not colliding
};

// known_colliding skips the containment test at s = 0 when the caller already
// knows P collides there.
Exit DirectionalExit(const PairGeometry& g, const Vector3& u, double slit_tol_abs,
                     bool known_colliding, DirectionalScratch* sc) {
  Vector3 e1, e2;
  Complete(u, &e1, &e2);
  const double eps = g.eps_len;
  Project(g.P, e1, e2, u, eps, &sc->proj_P, &sc->boxes_P);
  Project(g.S, e1, e2, u, eps, &sc->proj_S, &sc->boxes_S);

  // Intervals reaching s >= 0; the others are irrelevant to the exit.
  sc->intervals.clear();
  bool touching_at_zero = false;
  SweepPairs(sc->boxes_P, sc->boxes_S, &sc->active_P, &sc->active_S,
             [&](const Box2& bp, const Box2& bs) {
               if (bs.y0 > bp.y1 || bp.y0 > bs.y1) return false;
               if (bs.h1 - bp.h0 < -eps) return false;  // hi < 0 for sure
               const auto& tp = (*g.P.triangles)[bp.tri];
               const auto& ts = (*g.S.triangles)[bs.tri];
               const Proj a[3] = {sc->proj_P[tp[0]], sc->proj_P[tp[1]], sc->proj_P[tp[2]]};
               const Proj b[3] = {sc->proj_S[ts[0]], sc->proj_S[ts[1]], sc->proj_S[ts[2]]};
               const Interval iv = PairInterval(a, b, eps);
               if (iv.lo <= iv.hi && iv.hi >= 0.0) {
                 sc->intervals.emplace_back(iv.lo, iv.hi);
                 if (iv.lo <= 0.0) touching_at_zero = true;
               }
               return false;
             });

  Exit exit;
  exit.colliding = known_colliding || touching_at_zero || Contained(g, Vector3::Zero());
  if (!exit.colliding) return exit;

  // Merge, closing gaps thinner than the slit tolerance.
  auto& iv = sc->intervals;
  std::sort(iv.begin(), iv.end());
  size_t n = 0;
  for (size_t k = 0; k < iv.size(); ++k) {
    if (n > 0 && iv[k].first - iv[n - 1].second < slit_tol_abs) {
      iv[n - 1].second = std::max(iv[n - 1].second, iv[k].second);
    } else {
      iv[n++] = iv[k];
    }
  }
  iv.resize(n);

  // Walk the free gaps from s = 0; the first one where neither mesh contains
  // the other is the exit. Containment is constant inside a gap.
  // The first interval either contains 0 or, if P collides at 0 without
  // touching (containment), follows a gap that is not free.
  double s = 0.0;
  size_t k = 0;
  if (!iv.empty()) {
    s = iv[0].second;
    k = 1;
  }
  for (; k < iv.size(); ++k) {
    const double mid = 0.5 * (s + iv[k].first);
    if (!Contained(g, mid * u)) break;
    s = iv[k].second;
  }
  // Past the last interval the surfaces never meet again and P ends up far
  // away, so that gap is free.
  exit.distance = s;
  return exit;
}

// ---------------------------------------------------------------------------
// Triangle-triangle intersection for the collision test (closed triangles).

struct P2 {
  double x, y;
};

inline double Orient2(const P2& a, const P2& b, const P2& c) {
  return Cross2(b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y);
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

inline double Orient3(const Vector3& a, const Vector3& b, const Vector3& c, const Vector3& d) {
  return (b - a).cross(c - a).dot(d - a);
}

// Segment p-q against non-degenerate triangle t with normal n.
bool SegmentHitsTriangle(const Vector3& p, const Vector3& q, const Vector3* t,
                         const Vector3& n) {
  const double op = n.dot(p - t[0]), oq = n.dot(q - t[0]);
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

// Non-coplanar triangles meet iff an edge of one meets the other (the ends of
// their common segment lie on edges); coplanar ones iff an edge of one meets
// the other's region, which the in-plane segment test covers.
bool TrianglesIntersect(const Vector3* a, const Vector3* b) {
  const Vector3 na = (a[1] - a[0]).cross(a[2] - a[0]);
  const Vector3 nb = (b[1] - b[0]).cross(b[2] - b[0]);
  const bool deg_a = Degenerate(a, na), deg_b = Degenerate(b, nb);
  if (deg_a && deg_b) return false;
  if (!deg_b) {
    int pos = 0, neg = 0;
    for (int i = 0; i < 3; ++i) {
      const double d = nb.dot(a[i] - b[0]);
      pos += d > 0;
      neg += d < 0;
    }
    if (pos == 3 || neg == 3) return false;
  }
  if (!deg_a) {
    int pos = 0, neg = 0;
    for (int i = 0; i < 3; ++i) {
      const double d = na.dot(b[i] - a[0]);
      pos += d > 0;
      neg += d < 0;
    }
    if (pos == 3 || neg == 3) return false;
  }
  for (int i = 0; i < 3; ++i) {
    if (!deg_b && SegmentHitsTriangle(a[i], a[(i + 1) % 3], b, nb)) return true;
    if (!deg_a && SegmentHitsTriangle(b[i], b[(i + 1) % 3], a, na)) return true;
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

// ---------------------------------------------------------------------------
// Direction search.

std::vector<Vector3> FibonacciSphere(int n) {
  std::vector<Vector3> dirs;
  dirs.reserve(std::max(n, 0));
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden_angle * i;
    dirs.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  return dirs;
}

}  // namespace

double DirectionalPenetration(const TriangleMesh& probe, const Isometry3& X_WP,
                              bool probe_closed, const TriangleMesh& scene,
                              const Isometry3& X_WS, bool scene_closed, const Vector3& u_W,
                              double slit_tol_abs) {
  const double norm = u_W.norm();
  if (!(norm > 0.0)) return 0.0;
  const PairGeometry g = MakePair(probe, X_WP, probe_closed, scene, X_WS, scene_closed);
  DirectionalScratch scratch;
  return DirectionalExit(g, u_W / norm, slit_tol_abs, false, &scratch).distance;
}

ReferencePdResult ReferencePenetrationDepth(const TriangleMesh& probe, const Isometry3& X_WP,
                                            bool probe_closed, const TriangleMesh& scene,
                                            const Isometry3& X_WS, bool scene_closed,
                                            const ReferencePdOptions& options) {
  ReferencePdResult result;
  const PairGeometry g = MakePair(probe, X_WP, probe_closed, scene, X_WS, scene_closed);
  const double slit_tol_abs = options.slit_tol * g.size;
  DirectionalScratch scratch;

  std::vector<Vector3> dirs = FibonacciSphere(options.num_directions);
  for (const Vector3& d : options.extra_directions_W) {
    if (d.norm() > 0.0) dirs.push_back(d.normalized());
  }
  if (dirs.empty()) dirs.push_back(Vector3::UnitZ());

  const Exit first = DirectionalExit(g, dirs[0], slit_tol_abs, false, &scratch);
  result.directions_evaluated = 1;
  if (!first.colliding) return result;
  result.in_collision = true;

  auto evaluate = [&](const Vector3& u) {
    ++result.directions_evaluated;
    return DirectionalExit(g, u, slit_tol_abs, true, &scratch).distance;
  };
  std::vector<std::pair<double, int>> scored;
  scored.reserve(dirs.size());
  scored.emplace_back(first.distance, 0);
  for (int i = 1; i < static_cast<int>(dirs.size()); ++i) {
    scored.emplace_back(evaluate(dirs[i]), i);
  }
  std::sort(scored.begin(), scored.end());
  double best = scored[0].first;
  Vector3 best_u = dirs[scored[0].second];

  // Refine from the best directions that are not neighbours of one another.
  const double spacing = std::sqrt(4.0 * M_PI / std::max(options.num_directions, 1));
  const double min_separation_cos = std::cos(std::min(2.0 * spacing, M_PI));
  std::vector<Vector3> starts;
  std::vector<double> start_values;
  for (const auto& [value, i] : scored) {
    if (static_cast<int>(starts.size()) >= options.num_refine_starts) break;
    bool distinct = true;
    for (const Vector3& s : starts) distinct &= s.dot(dirs[i]) < min_separation_cos;
    if (distinct) {
      starts.push_back(dirs[i]);
      start_values.push_back(value);
    }
  }
  for (size_t k = 0; k < starts.size(); ++k) {
    // Opportunistic pattern search on the sphere with a shrinking angular step.
    Vector3 u = starts[k];
    double f = start_values[k];
    double step = spacing;
    for (int evals = 0; evals < options.refine_iterations;) {
      Vector3 e1, e2;
      Complete(u, &e1, &e2);
      const Vector3 moves[4] = {e1, e2, -e1, -e2};
      bool improved = false;
      for (const Vector3& m : moves) {
        if (evals >= options.refine_iterations) break;
        const Vector3 v = (std::cos(step) * u + std::sin(step) * m).normalized();
        const double fv = evaluate(v);
        ++evals;
        if (fv < f) {
          u = v;
          f = fv;
          improved = true;
          break;
        }
      }
      if (!improved) step *= 0.5;
    }
    if (f < best) {
      best = f;
      best_u = u;
    }
  }
  result.depth = best;
  result.direction_W = best_u;
  result.translation_W = best * best_u;
  return result;
}

bool ReferenceInCollision(const TriangleMesh& probe, const Isometry3& X_WP, bool probe_closed,
                          const TriangleMesh& scene, const Isometry3& X_WS, bool scene_closed,
                          const Vector3& t_W) {
  const PairGeometry g =
      MakePair(probe, TranslatedPose(X_WP, t_W), probe_closed, scene, X_WS, scene_closed);
  return SurfacesIntersect(g) || Contained(g, Vector3::Zero());
}

}  // namespace pd
