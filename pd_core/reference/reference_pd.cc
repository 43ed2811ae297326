#include "pd_core/reference/reference_pd.h"

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

// A contact normal in the (e1, e2, u) frame: unit and oriented along +u, or
// zero where undefined (features parallel to u).
struct Normal {
  double x = 0.0, y = 0.0, h = 0.0;
  // |u·n|: turns a gap length along u into its thickness; 1 if undefined.
  double cos() const { return h > 0.0 ? h : 1.0; }
};

inline Normal MakeNormal(double x, double y, double h) {
  const double norm = std::sqrt(x * x + y * y + h * h);
  if (!(norm > 0.0)) return {};
  const double scale = (h < 0.0 ? -1.0 : 1.0) / norm;
  return {x * scale, y * scale, h * scale};
}

// A touching interval with the contact normal at each end. Near-ties (within
// tol) keep the normal with the larger cosine, the conservative choice for
// slits.
struct Interval {
  double lo = kInf, hi = -kInf;
  Normal n_lo, n_hi;
  void Add(double s, const Normal& n, double tol) {
    if (s < lo - tol) {
      lo = s;
      n_lo = n;
    } else if (s <= lo + tol) {
      lo = std::min(lo, s);
      if (n.cos() > n_lo.cos()) n_lo = n;
    }
    if (s > hi + tol) {
      hi = s;
      n_hi = n;
    } else if (s >= hi - tol) {
      hi = std::max(hi, s);
      if (n.cos() > n_hi.cos()) n_hi = n;
    }
  }
};

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

// A projected triangle and what its pair tests need.
struct TriProj {
  Proj v[3];
  double ex[3], ey[3], eh[3];  // edge k = v[k+1] - v[k]
  double len1[3];              // L1 length of the projected edge k
  Normal n;                    // face normal; undefined when flat
  double orient = 1.0;         // sign of the projected area
  // Thinner than eps in projection, i.e. parallel to u: its face events are
  // replaced by events on its edges.
  bool flat = false;
};

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

// The closed set of s with (a + s u) intersecting b; empty if lo > hi.
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

// Per-direction buffers, reused across directions of one query.
struct DirectionalScratch {
  std::vector<Proj> proj_P, proj_S;
  std::vector<TriProj> tris_P, tris_S;
  std::vector<Box2> boxes_P, boxes_S;
  std::vector<std::vector<Box2>> bands_P, bands_S;
  std::vector<int> active_P, active_S;
  std::vector<Interval> intervals;
};

void Project(const PlacedMesh& m, const Vector3& e1, const Vector3& e2, const Vector3& u,
             double eps, std::vector<Proj>* proj, std::vector<TriProj>* tris,
             std::vector<Box2>* boxes) {
  proj->resize(m.p_OV.size());
  for (size_t v = 0; v < m.p_OV.size(); ++v) {
    const Vector3& p = m.p_OV[v];
    (*proj)[v] = {p.dot(e1), p.dot(e2), p.dot(u)};
  }
  boxes->resize(m.triangles->size());
  tris->resize(m.triangles->size());
  for (int t = 0; t < m.num_triangles(); ++t) {
    const auto& tri = (*m.triangles)[t];
    const Proj& a = (*proj)[tri[0]];
    const Proj& b = (*proj)[tri[1]];
    const Proj& c = (*proj)[tri[2]];
    (*tris)[t] = MakeTriProj(a, b, c, eps);
    (*boxes)[t] = {std::min({a.x, b.x, c.x}) - eps, std::max({a.x, b.x, c.x}) + eps,
                   std::min({a.y, b.y, c.y}) - eps, std::max({a.y, b.y, c.y}) + eps,
                   std::min({a.h, b.h, c.h}),       std::max({a.h, b.h, c.h}),
                   t};
  }
  std::sort(boxes->begin(), boxes->end(),
            [](const Box2& l, const Box2& r) { return l.x0 < r.x0; });
}

// Horizontal bands of equal height over the y range both meshes share.
struct Band {
  double y_min = 0.0, inv_height = 0.0;
  int count = 0;
  int Of(double y) const {
    return std::clamp(static_cast<int>((y - y_min) * inv_height), 0, count - 1);
  }
  void Insert(const Box2& box, std::vector<std::vector<Box2>>* bands) const {
    if (count == 0) return;
    const double y_max = y_min + count / inv_height;
    if (box.y1 < y_min || box.y0 > y_max) return;  // meets nothing of the other mesh
    for (int k = Of(box.y0), end = Of(box.y1); k <= end; ++k) (*bands)[k].push_back(box);
  }
};

// Bands about twice the mean box height: most boxes span one or two.
Band MakeBands(const std::vector<Box2>& a, const std::vector<Box2>& b) {
  Band band;
  if (a.empty() || b.empty()) return band;
  double a0 = kInf, a1 = -kInf, b0 = kInf, b1 = -kInf, height_sum = 0.0;
  for (const Box2& box : a) {
    a0 = std::min(a0, box.y0);
    a1 = std::max(a1, box.y1);
    height_sum += box.y1 - box.y0;
  }
  for (const Box2& box : b) {
    b0 = std::min(b0, box.y0);
    b1 = std::max(b1, box.y1);
    height_sum += box.y1 - box.y0;
  }
  const double y0 = std::max(a0, b0), y1 = std::min(a1, b1);
  if (!(y1 >= y0)) return band;
  constexpr int kMaxBands = 1024;
  const double mean_height = height_sum / static_cast<double>(a.size() + b.size());
  const double height = std::max(2.0 * mean_height, (y1 - y0) / kMaxBands);
  band.y_min = y0;
  band.count = std::clamp(static_cast<int>(std::ceil((y1 - y0) / height)), 1, kMaxBands);
  band.inv_height = band.count / std::max(y1 - y0, std::numeric_limits<double>::min());
  return band;
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
  // Unit contact normal where P leaves S, in world, oriented along u; zero if
  // undefined. Moving along it is locally the shortest way off that contact.
  Vector3 normal_W = Vector3::Zero();
};

// known_colliding skips the containment test at s = 0 when the caller already
// knows P collides there. With a finite cutoff (m) the caller only needs exits
// below it: pairs that touch only beyond it are skipped, and an exit at or
// beyond it is reported as infinity.
Exit DirectionalExit(const PairGeometry& g, const Vector3& u, double slit_tol_abs,
                     bool known_colliding, double cutoff, DirectionalScratch* sc) {
  Vector3 e1, e2;
  Complete(u, &e1, &e2);
  const double eps = g.eps_len;
  Project(g.P, e1, e2, u, eps, &sc->proj_P, &sc->tris_P, &sc->boxes_P);
  Project(g.S, e1, e2, u, eps, &sc->proj_S, &sc->tris_S, &sc->boxes_S);

  // Sort-and-sweep along x within bands of y (a plain sweep would compare
  // every pair in a column of the projection). Boxes go into each band they
  // span; a pair is handled in the band holding the larger of its y0.
  const Band bands = MakeBands(sc->boxes_P, sc->boxes_S);
  for (auto* b : {&sc->bands_P, &sc->bands_S}) {
    if (static_cast<int>(b->size()) < bands.count) b->resize(bands.count);
    for (int k = 0; k < bands.count; ++k) (*b)[k].clear();
  }
  for (const Box2& box : sc->boxes_P) bands.Insert(box, &sc->bands_P);
  for (const Box2& box : sc->boxes_S) bands.Insert(box, &sc->bands_S);

  // Intervals reaching s >= 0; the others are irrelevant to the exit.
  sc->intervals.clear();
  bool touching_at_zero = false;
  bool pruned = false;  // some pair touches only beyond the cutoff
  for (int band = 0; band < bands.count; ++band) {
    SweepPairs(sc->bands_P[band], sc->bands_S[band], &sc->active_P, &sc->active_S,
               [&](const Box2& bp, const Box2& bs) {
                 if (bs.y0 > bp.y1 || bp.y0 > bs.y1) return false;
                 if (bands.Of(std::max(bp.y0, bs.y0)) != band) return false;
                 if (bs.h1 - bp.h0 < -eps) return false;  // hi < 0 for sure
                 if (bs.h0 - bp.h1 > cutoff + eps) {      // lo > cutoff for sure
                   pruned = true;
                   return false;
                 }
                 const Interval iv = PairInterval(sc->tris_P[bp.tri], sc->tris_S[bs.tri], eps);
                 if (iv.lo > iv.hi || iv.hi < 0.0) return false;
                 if (iv.lo > cutoff) {
                   pruned = true;
                 } else {
                   sc->intervals.push_back(iv);
                   if (iv.lo <= 0.0) touching_at_zero = true;
                 }
                 return false;
               });
  }

  Exit exit;
  exit.colliding = known_colliding || touching_at_zero || Contained(g, Vector3::Zero());
  if (!exit.colliding) return exit;

  // Merge, closing slits: gaps whose length along u times the larger normal
  // cosine at their ends (their thickness, for parallel walls) is below the
  // slit tolerance. Intervals that touch (within eps) leave no gap at all.
  auto& iv = sc->intervals;
  std::sort(iv.begin(), iv.end(),
            [](const Interval& l, const Interval& r) { return l.lo < r.lo; });
  size_t n = 0;
  for (size_t k = 0; k < iv.size(); ++k) {
    if (n > 0) {
      Interval& last = iv[n - 1];
      const double gap = iv[k].lo - last.hi;
      if (gap <= eps || gap * std::max(last.n_hi.cos(), iv[k].n_lo.cos()) < slit_tol_abs) {
        if (iv[k].hi > last.hi + eps) {
          last.hi = iv[k].hi;
          last.n_hi = iv[k].n_hi;
        } else if (iv[k].hi >= last.hi - eps) {
          last.hi = std::max(last.hi, iv[k].hi);
          if (iv[k].n_hi.cos() > last.n_hi.cos()) last.n_hi = iv[k].n_hi;
        }
        continue;
      }
    }
    iv[n++] = iv[k];
  }
  iv.resize(n);

  // Walk the free gaps from s = 0; the first one where neither mesh contains
  // the other is the exit. Containment is constant inside a gap.
  // The first interval either contains 0 or, if P collides at 0 without
  // touching (containment), follows a gap that is not free.
  double s = 0.0;
  Normal n_s;
  size_t k = 0;
  if (!iv.empty()) {
    s = iv[0].hi;
    n_s = iv[0].n_hi;
    k = 1;
  }
  auto exit_at = [&](double distance) {
    exit.distance = distance;
    if (n_s.h > 0.0) exit.normal_W = n_s.x * e1 + n_s.y * e2 + n_s.h * u;
    return exit;
  };
  for (; k < iv.size() && s < cutoff; ++k) {
    const double mid = 0.5 * (s + iv[k].lo);
    if (!Contained(g, mid * u)) return exit_at(s);
    s = iv[k].hi;
    n_s = iv[k].n_hi;
  }
  exit.distance = kInf;
  if (s >= cutoff) return exit;
  // Past the last interval the surfaces never meet again and P ends up far
  // away, so that gap is free.
  if (!pruned) return exit_at(s);
  // The last gap runs past the cutoff to a skipped interval. If it may be a
  // slit, decide with all pairs.
  if ((cutoff - s) * n_s.cos() < slit_tol_abs) {
    return DirectionalExit(g, u, slit_tol_abs, known_colliding, kInf, sc);
  }
  if (!Contained(g, 0.5 * (s + cutoff) * u)) return exit_at(s);
  return exit;
}

// ---------------------------------------------------------------------------
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
  return DirectionalExit(g, u_W / norm, slit_tol_abs, false, kInf, &scratch).distance;
}

// A contact plane of the C-obstacle seen by one directional exit: P moved
// by t touches there, locally free where n·t >= c (n unit, c > 0).
struct ExitPlane {
  Vector3 n;
  double c;
};

// The shortest t with n_k·t >= c_k for every plane (a handful): the best
// over the active sets of one, two or three planes whose point is feasible.
// False when none is (contradictory planes).
bool ShortestInPlanes(const std::vector<ExitPlane>& planes, Vector3* t) {
  const int m = static_cast<int>(planes.size());
  double best = kInf;
  auto consider = [&](const Vector3& x) {
    if (!x.allFinite() || x.norm() >= best) return;
    for (const ExitPlane& p : planes)
      if (p.n.dot(x) < p.c * (1.0 - 1e-9)) return;
    best = x.norm();
    *t = x;
  };
  for (int a = 0; a < m; ++a) {
    consider(planes[a].c * planes[a].n);
    for (int b = a + 1; b < m; ++b) {
      const Vector3 &na = planes[a].n, &nb = planes[b].n;
      const double k = na.dot(nb), det = 1.0 - k * k;
      if (det > 1e-12)
        consider(((planes[a].c - k * planes[b].c) / det) * na +
                 ((planes[b].c - k * planes[a].c) / det) * nb);
      for (int c = b + 1; c < m; ++c) {
        Matrix3 A;
        A.row(0) = na.transpose();
        A.row(1) = nb.transpose();
        A.row(2) = planes[c].n.transpose();
        if (std::abs(A.determinant()) < 1e-9) continue;
        consider(A.inverse() * Vector3(planes[a].c, planes[b].c, planes[c].c));
      }
    }
  }
  return best < kInf;
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

  const Exit first = DirectionalExit(g, dirs[0], slit_tol_abs, false, kInf, &scratch);
  result.directions_evaluated = 1;
  if (!first.colliding) return result;
  result.in_collision = true;

  // Exits at or beyond `cutoff` come back as infinity, which saves the pairs
  // that only touch beyond it.
  auto evaluate = [&](const Vector3& u, double cutoff) {
    ++result.directions_evaluated;
    return DirectionalExit(g, u, slit_tol_abs, true, cutoff, &scratch);
  };
  // Sphere sweep: exits up to kStartSlack times the best so far are kept
  // exactly, as candidate starts for the refinement.
  constexpr double kStartSlack = 1.5;
  // Refinement evaluations see exits up to this many times the current best
  // (so a worse exit still reports its contact plane to the model).
  constexpr double kModelSlack = 1.5;
  std::vector<std::pair<double, int>> scored;
  std::vector<Vector3> normals(dirs.size(), Vector3::Zero());
  scored.reserve(dirs.size());
  scored.emplace_back(first.distance, 0);
  normals[0] = first.normal_W;
  double best = first.distance;
  for (int i = 1; i < static_cast<int>(dirs.size()); ++i) {
    const Exit e = evaluate(dirs[i], kStartSlack * best);
    best = std::min(best, e.distance);
    scored.emplace_back(e.distance, i);
    normals[i] = e.normal_W;
  }
  std::sort(scored.begin(), scored.end());
  Vector3 best_u = dirs[scored[0].second];

  // Refine from the best directions that are not neighbours of one another.
  const double spacing = std::sqrt(4.0 * M_PI / std::max(options.num_directions, 1));
  const double min_separation_cos = std::cos(std::min(2.0 * spacing, M_PI));
  std::vector<std::pair<double, int>> starts;
  for (const auto& [value, i] : scored) {
    if (static_cast<int>(starts.size()) >= options.num_refine_starts || value == kInf) break;
    bool distinct = true;
    for (const auto& start : starts) {
      distinct &= dirs[start.second].dot(dirs[i]) < min_separation_cos;
    }
    if (distinct) starts.emplace_back(value, i);
  }
  // Planes a refinement keeps from its exits near the current best.
  constexpr size_t kModelPlanes = 5;
  // A pattern step below this angle (rad) moves an exit by under 1e-7 of
  // its length: the start has converged.
  constexpr double kFinestStep = 1e-7;
  std::vector<ExitPlane> model;
  for (const auto& [start_value, start] : starts) {
    // Jump to the contact normal at the exit (for a single planar contact
    // that is the local optimum); else an opportunistic pattern search on
    // the sphere with a shrinking angular step, whose worse exits lend their
    // contact planes to a local model: at an optimum where two or three
    // contacts meet (a crease or corner of the C-obstacle) the pattern's
    // fixed axes zig-zag, the model's shortest point lands there.
    Vector3 u = dirs[start], n = normals[start];
    double f = start_value;
    model.clear();
    auto learn = [&](const Exit& e, const Vector3& v) {
      if (!(e.distance < kInf) || e.normal_W.squaredNorm() == 0.0) return;
      const ExitPlane p{e.normal_W, e.normal_W.dot(e.distance * v)};
      if (!(p.c > 0.0)) return;
      for (const ExitPlane& q : model)
        if (q.n.dot(p.n) > 1.0 - 1e-12 && std::abs(q.c - p.c) <= 1e-12 * g.size) return;
      if (model.size() >= kModelPlanes) model.erase(model.begin());
      model.push_back(p);
    };
    if (n.squaredNorm() > 0.0) learn(Exit{true, f, n}, u);
    auto normal_is_new = [&]() { return n.squaredNorm() > 0.0 && u.dot(n) < 1.0 - 1e-15; };
    bool try_normal = normal_is_new();
    double step = spacing;
    int evals = 0;
    // One evaluation along v: a shorter exit becomes the current one (its
    // normal is tried next), a longer one lends its plane to the model.
    auto try_direction = [&](const Vector3& v) {
      const Exit e = evaluate(v, kModelSlack * f);
      ++evals;
      if (!(e.distance < f)) {
        learn(e, v);
        return false;
      }
      u = v;
      f = e.distance;
      n = e.normal_W;
      learn(e, v);
      try_normal = normal_is_new();
      return true;
    };
    while (evals < options.refine_iterations && step > kFinestStep) {
      if (try_normal) {
        try_normal = false;
        try_direction(n);
        continue;
      }
      Vector3 e1, e2;
      Complete(u, &e1, &e2);
      const Vector3 moves[4] = {e1, e2, -e1, -e2};
      bool improved = false;
      for (const Vector3& m : moves) {
        if (evals >= options.refine_iterations) break;
        if ((improved = try_direction((std::cos(step) * u + std::sin(step) * m).normalized())))
          break;
      }
      // No pattern move gained: the model's shortest point, once, before
      // the step shrinks.
      Vector3 t_model;
      if (!improved && evals < options.refine_iterations && model.size() >= 2 &&
          ShortestInPlanes(model, &t_model) && t_model.normalized().dot(u) < 1.0 - 1e-15)
        improved = try_direction(t_model.normalized());
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
