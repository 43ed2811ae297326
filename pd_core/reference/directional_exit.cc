#include "pd_core/reference/directional_exit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pd_core/reference/ray_parity_containment.h"
#include "pd_core/reference/sweep_pairs.h"

namespace pd {
namespace reference {
namespace {

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

}  // namespace

void Complete(const Vector3& u, Vector3* e1, Vector3* e2) {
  const Vector3 a = std::abs(u.x()) < 0.9 ? Vector3::UnitX() : Vector3::UnitY();
  *e1 = a.cross(u).normalized();
  *e2 = u.cross(*e1);
}

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

}  // namespace reference
}  // namespace pd
